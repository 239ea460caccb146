#include "viewer/cli/RenderCommand.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "primitives/base/ParallelFor.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/cli/RenderJob.h"
#include "viewer/render/PngWriter.h"
#include "viewer/render/PreviewRender.h"

namespace viewer {

namespace {

// --preview keeps the quick headlight look (one ray per pixel, no shadows or secondary rays)
// for a fast glance at a heavy part; everything else is the Whitted renderer's job.
int previewCommand(const render::RenderJobOptions& o) {
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
    std::vector<std::string> rest(args.begin(), args.end());
    const auto preview = std::find(rest.begin(), rest.end(), "--preview");
    const bool isPreview = preview != rest.end();
    if (isPreview) rest.erase(preview);
    const render::RenderJobOptions o = render::parseRenderJobOptions(rest);
    if (o.common.help) {
        std::fputs(render::kRenderJobHelp, stdout);
        std::fputs("  --preview              a quick headlight look instead (PNG only)\n", stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    if (isPreview) {
        if (o.format != render::ImageFormat::Png)
            throw UsageError("render --preview writes PNG only");
        return previewCommand(o);
    }
    return render::runRenderJob(o);
}

}  // namespace viewer
