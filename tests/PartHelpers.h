// The part-language helpers the tests share: a part's text evaluated under a curve mode (as
// `csgray --curves` would), its diagnostics as text, its compiled scene (an evaluation error
// fails the calling test, with the diagnostics), and the spans of a whole line through it
// checked against spans derived by hand, and the rows of an extruded 2-D part.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

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

// The first diagnostic of a severity, formatted ("<none>" when there is none).
inline std::string firstDiagnostic(const io::EvaluateResult& r, io::Severity severity) {
    for (const io::Diagnostic& d : r.diagnostics)
        if (d.severity == severity) return io::formatDiagnostic(d);
    return "<none>";
}

inline csg::Scene compiled(const std::string& text, io::CurveMode curves = io::CurveMode::Auto,
                           const std::string& name = "part.scad") {
    const io::EvaluateResult r = evaluate(text, curves, name);
    EXPECT_TRUE(r.ok()) << diagnosticsOf(r);
    return csg::Scene::compile(r.ok() ? r.model->root : nullptr);
}

struct Interval {
    double in, out;
};

// The spans of the whole line o + t d through the scene's solid; dropTouches leaves out the
// zero-length spans of a line that only touches it.
inline std::vector<Interval> spansOf(const csg::Scene& scene, Vec3 o, Vec3 d,
                                     bool dropTouches = false) {
    csg::QueryContext ctx;
    const csg::Ray ray{o, d, -csg::kInfinity, csg::kInfinity};
    std::vector<Interval> out;
    for (const csg::Span& s : scene.spans(ray, ctx))
        if (!dropTouches || s.out.t > s.in.t) out.push_back({s.in.t, s.out.t});
    return out;
}

// The line's spans are expected, in order, each end within tol.
inline void expectSpans(const csg::Scene& scene, Vec3 o, Vec3 d,
                        const std::vector<Interval>& expected, double tol,
                        bool dropTouches = false) {
    const auto got = spansOf(scene, o, d, dropTouches);
    ASSERT_EQ(got.size(), expected.size()) << "ray from " << o.x << "," << o.y << "," << o.z
                                           << " along " << d.x << "," << d.y << "," << d.z;
    for (size_t i = 0; i < got.size(); ++i) {
        EXPECT_NEAR(got[i].in, expected[i].in, tol) << "span " << i;
        EXPECT_NEAR(got[i].out, expected[i].out, tol) << "span " << i;
    }
}

// The spans of the ray o + t d, t >= 0, through the scene as (in, out) pairs.
inline std::vector<std::pair<double, double>> spanPairs(const csg::Scene& scene, Vec3 o, Vec3 d) {
    csg::QueryContext ctx;
    std::vector<std::pair<double, double>> out;
    for (const csg::Span& s : scene.spans(csg::Ray{o, d, 0.0, csg::kInfinity}, ctx))
        out.push_back({s.in.t, s.out.t});
    return out;
}

// Two span lists given as (in, out) pairs: the same count, in order, each end within tol.
inline void expectSpanPairs(const std::vector<std::pair<double, double>>& got,
                            const std::vector<std::pair<double, double>>& want, double tol) {
    ASSERT_EQ(got.size(), want.size()) << "got " << got.size() << " spans";
    for (size_t i = 0; i < want.size(); ++i) {
        EXPECT_NEAR(got[i].first, want[i].first, tol) << "span " << i;
        EXPECT_NEAR(got[i].second, want[i].second, tol) << "span " << i;
    }
}

// Along x at height y through a 2-D part extruded to z in [0, 1]: the spans in x (zero-length
// touches of arcs left out).
inline void expectRow(const csg::Scene& scene, double y, std::vector<Interval> xs, double tol) {
    for (Interval& i : xs) i.in += 100.0, i.out += 100.0;
    expectSpans(scene, {-100.0, y, 0.5}, {1, 0, 0}, xs, tol, true);
}

}  // namespace csg::testing
