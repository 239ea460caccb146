// `csgray render`: a part to an image by the Whitted renderer (viewer/render/), or --preview.
// From the command line to files: load and compile the part, frame the camera, derive the
// effects plan, render the tiles, write the image (and --stats) atomically. Ctrl-C at any
// point before the image is written stops the command with nothing written.
// Under mpirun (or with --resume) the tiles, or an animation's frames, go through RenderFarm:
// rank 0 hands them out to every rank and writes the image; the bytes are those of a single
// process.
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
#include "viewer/cli/JobKey.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/cli/RenderFarm.h"
#include "viewer/cli/Report.h"
#include "viewer/cli/dist/Journal.h"
#include "viewer/cli/dist/Ranks.h"
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
    "  --preview              a quick headlight look instead (PNG only)\n"
    "  --frames A:B           OpenSCAD's animation: frames A to B (both included) of\n"
    "                         --animate N steps, $t = frame / N as `openscad --animate N`\n"
    "                         steps it (N defaults to B + 1); frame f is written to OUT with\n"
    "                         f in 5 digits before the extension (out.png: out00007.png)\n"
    "  --animate N            N animation steps (alone: all N frames, as OpenSCAD's option)\n"
    "  --resume               keep a journal of finished tiles (frames) in OUT.journal; a job\n"
    "                         run again with the same options does only what is missing\n"
    "\n"
    "Under mpirun or srun (`mpirun -np 4 csgray render ...`) the tiles, or the frames, are\n"
    "spread over the ranks (each with --threads threads) and rank 0 writes the files: the\n"
    "same bytes as one process makes. Every rank reads the part; files must be on a file\n"
    "system every rank sees.\n";

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
    bool resume = false;   // --resume
    // --frames A:B (both included) of `animate` steps; none: one still image at $t = 0.
    std::optional<std::pair<int, int>> frames;
    int animate = 0;  // --animate N; 0: B + 1
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
        .key("slabCulls")
        .value(result.queries.slabCulls)
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
        } else if (auto frames = cursor.option("--frames")) {
            const size_t colon = frames->find(':');
            if (colon == std::string::npos)
                throw UsageError("--frames expects A:B (first and last frame), got '" + *frames +
                                 "'");
            const auto frame = [&](std::string_view text) {
                return text == "0" ? 0 : parsePositiveInt(text, "--frames", 99999);
            };
            o.frames = {frame(std::string_view(*frames).substr(0, colon)),
                        frame(std::string_view(*frames).substr(colon + 1))};
            if (o.frames->first > o.frames->second)
                throw UsageError("--frames A:B needs A <= B, got '" + *frames + "'");
        } else if (auto animate = cursor.option("--animate")) {
            o.animate = parsePositiveInt(*animate, "--animate", 100000);
        } else if (cursor.flag("--resume")) {
            o.resume = true;
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
    if (o.animate > 0 && !o.frames) o.frames = {0, o.animate - 1};
    if (o.frames) {
        if (o.animate == 0) o.animate = o.frames->second + 1;
        if (o.frames->second >= o.animate)
            throw UsageError("--frames: the last frame of --animate " + std::to_string(o.animate) +
                             " is " + std::to_string(o.animate - 1));
        if (!o.statsFile.empty()) throw UsageError("--stats is for one image, not --frames");
        if (o.preview) throw UsageError("--preview renders one image, not --frames");
    }
    return o;
}

// What decides a render's bytes beyond the part (JobKey.h): the image's size, sampling, format
// and effects, and the frames of an animation.
std::string renderKey(const RenderOptions& o) {
    char line[256];
    std::snprintf(line, sizeof line, "%d %d %d %d %a %d %d %d %d %d", o.width, o.height,
                  o.samplesPerAxis, int(o.format), o.plan.minWeight, o.plan.maxDepth,
                  int(o.plan.shadows), o.frames ? o.frames->first : -1,
                  o.frames ? o.frames->second : -1, o.animate);
    return jobKey("render", o.common, line);
}

// One Whitted image; returns the exit code (kExitInterrupted after Ctrl-C). With ranks, every
// rank of the job runs this together and the tiles go through the farm (rank 0 writes the
// image); without, this process renders it alone on its threads.
int renderStill(const RenderOptions& o, const dist::Ranks* ranks) {
    render::InterruptGuard interruptGuard;
    const std::atomic<bool>& interrupted = render::interruptRequested();
    PhaseSeconds seconds;
    const bool root = !ranks || ranks->root();

    Report report(o.common.jsonDiagnostics);
    LoadedPart part;
    auto start = Clock::now();
    const int loaded = loadPart(o.common, report, part);
    if (ranks && !ranks->allOk(loaded == kExitOk)) {
        if (loaded == kExitOk && root) report.error(o.common.part, "another rank cannot load it");
        return loaded != kExitOk ? loaded : kExitBadModel;
    }
    if (loaded != kExitOk) return loaded;
    seconds.load = secondsSince(start);
    if (interrupted && !ranks) return render::kExitInterrupted;

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
    render::ProgressMeter progress(render::ProgressMeter::styleFor(o.quiet || !root));
    const render::RenderCamera rays(camera, o.width, o.height);
    render::RenderResult result;
    ResumeJournal resume;
    if (ranks) {
        if (o.resume && root) {
            resume.path = dist::journalPathFor(o.output);
            resume.key = renderKey(o);
        }
        const int code = renderTilesOnRanks(*ranks, part.scene, plan, rays, image,
                                            o.resume && root ? &resume : nullptr, &progress,
                                            &interrupted, result, report);
        if (!root || code != kExitOk) return code;
    } else {
        result = render::renderImage(part.scene, plan, rays, image, &interrupted, &progress);
        if (result.interrupted || interrupted) return render::kExitInterrupted;
    }
    seconds.render = secondsSince(start);

    start = Clock::now();
    if (const std::string error = render::writeImage(o.output, o.format, result); !error.empty()) {
        report.error(o.output, error);
        return kExitIo;
    }
    if (resume.journal.isOpen()) resume.journal.remove();
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

// OpenSCAD's name for frame f of an animation written to output: f in five digits before the
// extension (openscad.cc, cmdline: out.png gives out00000.png, out00001.png, ...).
std::string frameFileName(const std::string& output, int frame) {
    std::filesystem::path path(output);
    const std::filesystem::path extension = path.extension();
    path.replace_extension();
    char digits[16];
    std::snprintf(digits, sizeof digits, "%05d", frame);
    path += digits;
    path += extension;
    return path.string();
}

// --frames: each frame a whole image at $t = frame / animate (OpenSCAD's step), rendered alone
// by one rank on its threads and written by that rank; rank 0 hands the frames out.
int renderAnimation(const RenderOptions& o, const dist::Ranks& ranks) {
    std::vector<int> frames;
    for (int f = o.frames->first; f <= o.frames->second; ++f) frames.push_back(f);
    const auto renderFrame = [&](int frame) {
        RenderOptions one = o;
        one.frames.reset();
        one.common.time = frame * (1.0 / o.animate);  // OpenSCAD's expression, bit for bit
        one.output = frameFileName(o.output, frame);
        one.quiet = true;
        return renderStill(one, nullptr);
    };
    const auto written = [&](int frame) {
        std::error_code error;
        return std::filesystem::exists(frameFileName(o.output, frame), error);
    };
    Report report(o.common.jsonDiagnostics);
    render::ProgressMeter progress(render::ProgressMeter::styleFor(o.quiet || !ranks.root()));
    ResumeJournal resume;
    resume.path = dist::journalPathFor(o.output);
    resume.key = renderKey(o);
    const int code =
        renderFramesOnRanks(ranks, frames, renderFrame, written,
                            o.resume && ranks.root() ? &resume : nullptr, &progress, report);
    if (code == kExitOk && resume.journal.isOpen()) resume.journal.remove();
    return code;
}

int runWhitted(const RenderOptions& o) {
    const dist::Ranks& ranks = dist::Ranks::job();
    if (o.frames) return renderAnimation(o, ranks);
    // Alone and without a journal, the plain threaded render of before.
    return renderStill(o, ranks.mpi() || o.resume ? &ranks : nullptr);
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
        if (!dist::Ranks::job().root()) return kExitOk;  // under mpirun: once, by rank 0
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
