#include "viewer/cli/LoadPart.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "io/Evaluate.h"

namespace viewer {

int loadPart(const CommonOptions& options, Report& report, LoadedPart& part) {
    // An unreadable main file is an I/O failure (exit 3), which evaluateFile cannot tell
    // apart from a bad model, so it is checked here first. A missing include stays a model
    // error: the model names a file that is not there.
    {
        std::ifstream probe(options.part, std::ios::binary);
        if (!probe) {
            report.error(options.part, std::string("cannot open the part: ") +
                                           std::strerror(errno ? errno : ENOENT));
            return kExitIo;
        }
    }

    io::EvaluateOptions evaluateOptions;
    evaluateOptions.defines = options.defines;
    evaluateOptions.curves = options.curves;
    evaluateOptions.time = options.time;
    evaluateOptions.echo = [&report](const std::string& line) { report.echo(line); };
    io::EvaluateResult result = io::evaluateFile(options.part, evaluateOptions);
    report.addAll(result.diagnostics);
    if (!result.ok()) return kExitBadModel;

    part.model = std::move(*result.model);
    try {
        part.scene = csg::Scene::compile(part.model.root, {.accel = options.accel,
                                                           .polygonMethod = options.polygonMethod,
                                                           .slabs = options.slabs});
    } catch (const csg::CompileError& e) {
        report.add(io::diagnosticAt(part.model, e.source, io::Severity::Error, e.what()));
        return kExitBadModel;
    }
    return kExitOk;
}

int requireSolids(const LoadedPart& part, Report& report, std::string_view command) {
    if (part.model.twoD) {
        const uint32_t tag = part.model.root ? part.model.root->tags.source : 0;
        report.add(io::diagnosticAt(part.model, tag, io::Severity::Error,
                                    std::string(command) +
                                        ": the top level object is not a 3-D object, as OpenSCAD "
                                        "says: a 2-D part has no volume to mesh or measure "
                                        "(extrude it with linear_extrude or rotate_extrude)"));
        return kExitBadModel;
    }
    for (uint32_t leaf = 0; leaf < part.scene.leafCount(); ++leaf) {
        if (!csg::isSheet(part.scene.leafPrimitive(leaf))) continue;
        report.add(io::diagnosticAt(
            part.model, part.scene.leafTags(leaf).source, io::Severity::Error,
            std::string(command) + ": a surface (solid=false) has no volume; only solids "
                                   "can be meshed or measured (declare a closed patch set "
                                   "solid=true)"));
        return kExitBadModel;
    }
    return kExitOk;
}

}  // namespace viewer
