// What the fuzzer (fuzz_io.cpp) and the corpus replay test (fuzz_replay.cpp) do with one input:
// evaluate it as a part under tight limits, check the io boundary's promises, and compile and
// probe the model it gives. Any crash, hang, sanitizer report or abort() here is a bug.
#pragma once

#include <cstdlib>
#include <string>
#include <string_view>

#include "csg/Scene.h"
#include "io/Evaluate.h"

namespace fuzz {

// Small limits keep one input well under a second even under the sanitizers; the evaluator
// must turn anything bigger into a diagnostic rather than a hang.
inline io::EvaluateOptions fuzzOptions() {
    io::EvaluateOptions options;
    options.maxCallDepth = 100;
    options.maxSteps = 1'000'000;
    options.allowFiles = false;  // include </dev/stdin> must not block, nor read the disk
    options.echo = [](const std::string&) {};
    return options;
}

// Every curve mode gets its share of the inputs, by their length (stable across runs, so that
// the corpus replays as it was fuzzed): openscad builds faceted solids and OpenSCAD's sliced
// extrusions, exact and auto the exact ones.
inline io::CurveMode curveModeFor(std::string_view text) {
    constexpr io::CurveMode kModes[] = {io::CurveMode::Auto, io::CurveMode::OpenScad,
                                        io::CurveMode::Exact};
    return kModes[text.size() % 3];
}

inline void evaluateInput(std::string_view text) {
    io::EvaluateOptions options = fuzzOptions();
    options.curves = curveModeFor(text);
    const io::EvaluateResult result = io::evaluateString(text, "fuzz.scad", options);
    // A model exactly when no diagnostic is an error, and every diagnostic formats.
    if (result.ok() == io::hasErrors(result.diagnostics)) std::abort();
    for (const io::Diagnostic& d : result.diagnostics)
        if (io::formatDiagnostic(d).empty() || d.message.empty()) std::abort();
    (void)io::diagnosticsToJson(result.diagnostics);
    if (!result.ok()) return;
    // The model compiles or names the node it cannot compile; then one ray is answered.
    try {
        const csg::Scene scene = csg::Scene::compile(result.model->root);
        csg::QueryContext context;
        const csg::Ray ray{csg::Vec3(-100.0, -0.3, 0.2), csg::Vec3(1.0, 0.01, 0.002), 0.0, 1e6};
        (void)scene.spans(ray, context);
        (void)scene.closest(ray, context);
    } catch (const csg::CompileError& e) {
        (void)io::diagnosticAt(*result.model, e.source, io::Severity::Error, e.what());
    }
}

}  // namespace fuzz
