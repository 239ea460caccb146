#include "viewer/RenderCommand.h"

#include <cstdio>
#include <thread>

#include "io/PngWriter.h"
#include "viewer/Cli.h"
#include "viewer/LoadPart.h"
#include "viewer/PreviewRender.h"

namespace viewer {

namespace {

const char* const kRenderHelp =
    "usage: csgray render PART -o OUT.png [--size WxH] [options]\n"
    "\n"
    "Renders the part to a PNG image: one ray per pixel, the material color lit by a light\n"
    "at the eye. The camera is the part's camera(...) or one that frames the whole part.\n"
    "The file is written atomically: on any failure no file (and no partial file) is left.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE      the image to write (.png)\n"
    "  --size WxH             image size in pixels (default 800x600)\n"
    "  --threads N            rendering threads (default: all cores)\n";

struct RenderOptions {
    CommonOptions common;
    std::string output;
    int width = 800, height = 600;
    int threads = 0;  // 0: all cores
};

RenderOptions parseRenderOptions(std::span<const std::string> args) {
    RenderOptions o;
    ArgCursor cursor(args);
    while (!cursor.done()) {
        std::optional<std::string> out = cursor.option("-o");
        if (!out) out = cursor.option("--output");
        if (out) {
            o.output = *out;
        } else if (auto size = cursor.option("--size")) {
            std::tie(o.width, o.height) = parseSize(*size, "--size");
        } else if (auto threads = cursor.option("--threads")) {
            o.threads = parsePositiveInt(*threads, "--threads", 1024);
        } else if (!cursor.common(o.common)) {
            throw UsageError("render: unknown option '" + cursor.peek() + "'");
        }
    }
    if (o.common.help) return o;
    requirePart(o.common, "render");
    if (o.output.empty()) throw UsageError("render needs an output file: -o OUT.png");
    std::string extension = std::filesystem::path(o.output).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".png")
        throw UsageError(
            "render: the output format is chosen by extension; only .png is "
            "supported, got '" +
            o.output + "'");
    if (int64_t(o.width) * o.height > int64_t(1) << 28)
        throw UsageError("--size: at most 2^28 pixels");
    return o;
}

}  // namespace

int renderCommand(std::span<const std::string> args) {
    const RenderOptions o = parseRenderOptions(args);
    if (o.common.help) {
        std::fputs(kRenderHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    Report report(o.common.jsonDiagnostics);
    LoadedPart part;
    if (const int code = loadPart(o.common, report, part); code != kExitOk) return code;

    const int threads =
        o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    const io::Rgb8Image image = renderPreview(part.model, part.scene, o.width, o.height, threads);
    if (const std::string error = io::writePng(o.output, image); !error.empty()) {
        report.error(o.output, error);
        return kExitIo;
    }
    return kExitOk;
}

}  // namespace viewer
