// The part-language helpers the tests share: a part's text evaluated under a curve mode (as
// `csgray --curves` would), its diagnostics as text, and its compiled scene (an evaluation
// error fails the calling test, with the diagnostics).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "csg/Scene.h"
#include "io/Diagnostic.h"
#include "io/Evaluate.h"

namespace csg::testing {

inline io::EvaluateResult evaluate(const std::string& text,
                                   io::CurveMode curves = io::CurveMode::Auto,
                                   const std::string& name = "part.scad") {
    io::EvaluateOptions options;
    options.curves = curves;
    return io::evaluateString(text, name, options);
}

inline std::string diagnosticsOf(const io::EvaluateResult& r) {
    std::string all;
    for (const io::Diagnostic& d : r.diagnostics) all += io::formatDiagnostic(d) + "\n";
    return all;
}

inline csg::Scene compiled(const std::string& text, io::CurveMode curves = io::CurveMode::Auto,
                           const std::string& name = "part.scad") {
    const io::EvaluateResult r = evaluate(text, curves, name);
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    return csg::Scene::compile(r.ok() ? r.model->root : nullptr);
}

}  // namespace csg::testing
