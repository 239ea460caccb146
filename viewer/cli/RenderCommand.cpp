// `csgray render`: a part to an image by the Whitted renderer (viewer/render/), or --preview.
// From the command line to files: load and compile the part, frame the camera, derive the
// effects plan, render the tiles, write the image (and --stats) atomically. Ctrl-C at any
// point before the image is written stops the command with nothing written.
#include "viewer/cli/RenderCommand.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "primitives/base/AtomicFile.h"
#include "primitives/base/Json.h"
#include "primitives/base/ParallelFor.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/cli/Report.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/ImageOutput.h"
#include "viewer/render/Interrupt.h"
#include "viewer/render/PngWriter.h"
#include "viewer/render/PreviewRender.h"
#include "viewer/render/Progress.h"
#include "viewer/render/RenderCamera.h"
#include "viewer/render/TileRenderer.h"

namespace viewer {

namespace {

constexpr const char* kRenderHelp =
    "usage: csgray render PART -o OUT.png [options]\n"
    "\n"
    "Ray traces the part (Whitted: ambient, Lambert diffuse, Blinn-Phong specular, hard\n"
    "shadows, mirror reflection, refraction) and writes the image. Only the effects the\n"
    "scene can show are simulated (the effects plan, see --stats and `csgray info`). The\n"
    "camera is the part's camera(...) or one that frames the part; the lights are its\n"
    "light(...)s or one light over the viewer's left shoulder. Files are written\n"
    "atomically: on failure or Ctrl-C (exit 130) no file and no partial file is left.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE      the image to write (.png; .pfm or .exr for linear float RGB)\n"
    "  --format png|pfm|exr   the image format (default: by the output's extension)\n"
    "  --size WxH             image size in pixels (default 800x600)\n"
    "  --aa N                 N x N stratified samples per pixel, deterministic (default 1)\n"
    "  --threads N            rendering threads (default: all cores)\n"
    "  --no-shadows           cast no shadow rays (lights reach every surface facing them)\n"
    "  --min-weight W         end a ray tree branch whose weight falls below W\n"
    "                         (default 1/256 = 0.00390625)\n"
    "  --max-depth N          at most N reflection/refraction bounces (default 10)\n"
    "  --stats FILE.json      rays by kind, query work, time per phase and the plan\n"
    "  --quiet                no progress on stderr\n"
    "  --preview              a quick headlight look instead (PNG only)\n";

struct RenderOptions {
    CommonOptions common;
    std::string output;
    render::ImageFormat format = render::ImageFormat::Png;
    int width = 800, height = 600;
    int samplesPerAxis = 1;  // --aa
    int threads = 0;         // 0: all cores
    render::PlanSettings plan;
    std::string statsFile;  // --stats; empty: none
    bool quiet = false;
    bool preview = false;  // --preview
};

// Each image format's --format name, which is also its file extension.
std::optional<render::ImageFormat> formatNamed(std::string_view name) {
    struct Named {
        std::string_view name;
        render::ImageFormat format;
    };
    static constexpr Named kFormats[] = {{"png", render::ImageFormat::Png},
                                         {"pfm", render::ImageFormat::Pfm},
                                         {"exr", render::ImageFormat::Exr}};
    for (const Named& f : kFormats)
        if (f.name == name) return f.format;
    return std::nullopt;
}

std::string lowerExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct PhaseSeconds {
    double load = 0, plan = 0, render = 0, write = 0;
};

std::string statsJson(const RenderOptions& o, int threads, const PhaseSeconds& seconds,
                      const render::RenderResult& result, const render::EffectsPlan& plan) {
    std::string out;
    csg::JsonWriter json(out);
    json.beginObject();
    json.key("part").value(o.common.part);
    json.key("image")
        .beginObject()
        .key("width")
        .value(o.width)
        .key("height")
        .value(o.height)
        .key("aa")
        .value(o.samplesPerAxis)
        .key("threads")
        .value(threads)
        .endObject();
    const render::RayCounts& r = result.rays;
    json.key("rays")
        .beginObject()
        .key("primary")
        .value(r.primary)
        .key("shadow")
        .value(r.shadow)
        .key("reflection")
        .value(r.reflection)
        .key("refraction")
        .value(r.refraction)
        .key("total")
        .value(r.total())
        .endObject();
    json.key("queries")
        .beginObject()
        .key("rays")
        .value(result.queries.rays)
        .key("nodeVisits")
        .value(result.queries.nodeVisits)
        .key("primitiveTests")
        .value(result.queries.primitiveTests)
        .endObject();
    // "load" is evaluation and compilation together: loadPart does both in one call.
    json.key("seconds")
        .beginObject()
        .key("loadAndCompile")
        .value(seconds.load)
        .key("plan")
        .value(seconds.plan)
        .key("render")
        .value(seconds.render)
        .key("write")
        .value(seconds.write)
        .key("total")
        .value(seconds.load + seconds.plan + seconds.render + seconds.write)
        .endObject();
    json.key("plan");
    render::writeEffectsPlan(json, plan);
    json.endObject();
    out += '\n';
    return out;
}

// Parses the arguments after "render" (throws UsageError).
RenderOptions parseRenderOptions(std::span<const std::string> args) {
    RenderOptions o;
    // --preview is taken out wherever it stands, before the other options are read.
    std::vector<std::string> rest(args.begin(), args.end());
    if (const auto preview = std::find(rest.begin(), rest.end(), "--preview");
        preview != rest.end()) {
        rest.erase(preview);
        o.preview = true;
    }
    std::string format;
    ArgCursor cursor(rest);
    while (!cursor.done()) {
        std::optional<std::string> out = cursor.option("-o");
        if (!out) out = cursor.option("--output");
        if (out) {
            o.output = *out;
        } else if (auto size = cursor.option("--size")) {
            std::tie(o.width, o.height) = parseSize(*size, "--size");
        } else if (auto threads = cursor.option("--threads")) {
            o.threads = parsePositiveInt(*threads, "--threads", 1024);
        } else if (auto aa = cursor.option("--aa")) {
            o.samplesPerAxis = parsePositiveInt(*aa, "--aa", 16);
        } else if (auto weight = cursor.option("--min-weight")) {
            o.plan.minWeight = parseNumberIn(*weight, "--min-weight", 0.0, 1.0);
        } else if (auto depth = cursor.option("--max-depth")) {
            o.plan.maxDepth = *depth == "0" ? 0 : parsePositiveInt(*depth, "--max-depth", 64);
        } else if (auto stats = cursor.option("--stats")) {
            o.statsFile = *stats;
        } else if (auto f = cursor.option("--format")) {
            format = *f;
        } else if (cursor.flag("--no-shadows")) {
            o.plan.shadows = false;
        } else if (cursor.flag("--quiet") || cursor.flag("-q")) {
            o.quiet = true;
        } else if (!cursor.common(o.common)) {
            throw UsageError("render: unknown option '" + cursor.peek() + "'");
        }
    }
    if (o.common.help) return o;
    requirePart(o.common, "render");
    if (o.output.empty()) throw UsageError("render needs an output file: -o OUT.png");
    if (!format.empty()) {
        const std::optional<render::ImageFormat> named = formatNamed(format);
        if (!named) throw UsageError("--format: expected png, pfm or exr, got '" + format + "'");
        o.format = *named;
    } else {
        const std::string extension = lowerExtension(o.output);
        const std::optional<render::ImageFormat> named =
            formatNamed(extension.empty() ? extension : extension.substr(1));
        if (!named)
            throw UsageError("render: cannot tell the format of '" + o.output +
                             "'; use a .png, .pfm or .exr name, or --format png|pfm|exr");
        o.format = *named;
    }
    if (int64_t(o.width) * o.height > int64_t(1) << 28)
        throw UsageError("--size: at most 2^28 pixels");
    return o;
}

// The Whitted render; returns the exit code (kExitInterrupted after Ctrl-C).
int runWhitted(const RenderOptions& o) {
    render::InterruptGuard interruptGuard;
    const std::atomic<bool>& interrupted = render::interruptRequested();
    PhaseSeconds seconds;

    Report report(o.common.jsonDiagnostics);
    LoadedPart part;
    auto start = Clock::now();
    if (const int code = loadPart(o.common, report, part); code != kExitOk) return code;
    seconds.load = secondsSince(start);
    if (interrupted) return render::kExitInterrupted;

    start = Clock::now();
    const double aspect = double(o.width) / double(o.height);
    const render::Camera camera =
        part.model.camera ? *part.model.camera : render::frameBounds(part.scene, aspect);
    const render::EffectsPlan plan =
        render::makeEffectsPlan(part.model, part.model.root.get(), part.scene, camera, o.plan);
    seconds.plan = secondsSince(start);

    render::ImageSettings image;
    image.width = o.width;
    image.height = o.height;
    image.samplesPerAxis = o.samplesPerAxis;
    image.threads = csg::resolveThreads(o.threads);
    image.store = render::pixelStoreFor(o.format);
    start = Clock::now();
    render::ProgressMeter progress(render::ProgressMeter::styleFor(o.quiet));
    const render::RenderResult result =
        render::renderImage(part.scene, plan, render::RenderCamera(camera, o.width, o.height),
                            image, &interrupted, &progress);
    seconds.render = secondsSince(start);
    if (result.interrupted || interrupted) return render::kExitInterrupted;

    start = Clock::now();
    if (const std::string error = render::writeImage(o.output, o.format, result); !error.empty()) {
        report.error(o.output, error);
        return kExitIo;
    }
    seconds.write = secondsSince(start);

    if (!o.statsFile.empty()) {
        const std::string json = statsJson(o, image.threads, seconds, result, plan);
        if (const std::string error = csg::writeFileAtomically(o.statsFile, json); !error.empty()) {
            report.error(o.statsFile, error);
            return kExitIo;
        }
    }
    return kExitOk;
}

// --preview keeps the quick headlight look (one ray per pixel, no shadows or secondary rays)
// for a fast glance at a heavy part; everything else is the Whitted renderer's job.
int runPreview(const RenderOptions& o) {
    Report report(o.common.jsonDiagnostics);
    LoadedPart part;
    if (const int code = loadPart(o.common, report, part); code != kExitOk) return code;
    const int threads = csg::resolveThreads(o.threads);
    const render::Rgb8Image image =
        render::renderPreview(part.model, part.scene, o.width, o.height, threads);
    if (const std::string error = render::writePng(o.output, image); !error.empty()) {
        report.error(o.output, error);
        return kExitIo;
    }
    return kExitOk;
}

}  // namespace

int renderCommand(std::span<const std::string> args) {
    const RenderOptions o = parseRenderOptions(args);
    if (o.common.help) {
        std::fputs(kRenderHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    if (o.preview) {
        if (o.format != render::ImageFormat::Png)
            throw UsageError("render --preview writes PNG only");
        return runPreview(o);
    }
    return runWhitted(o);
}

}  // namespace viewer
