// surface(f, bbox, solver) in the part language: f expands to the right polynomial (a sphere
// written as a surface answers rays as sphere() does), solver names map onto the enum, and
// every bad argument is an error at its file:line:col (inside f at the offending character).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "csg/Scene.h"
#include "io/Evaluate.h"

using namespace io;

namespace {

EvaluateResult run(const std::string& source) {
    return evaluateString(source, "test.scad");
}

// The first error of a part that must fail, formatted as the command line prints it.
std::string error(const std::string& source) {
    EvaluateResult r = run(source);
    EXPECT_FALSE(r.ok()) << source;
    for (const auto& d : r.diagnostics)
        if (d.severity == Severity::Error) return formatDiagnostic(d);
    return "<no error>";
}

csg::Scene scene(const std::string& source) {
    EvaluateResult r = run(source);
    EXPECT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : formatDiagnostic(r.diagnostics[0]));
    return csg::Scene::compile(r.ok() ? r.model->root : nullptr);
}

const csg::AlgebraicSurface* surfaceOf(const EvaluateResult& r) {
    if (!r.ok() || !r.model->root) return nullptr;
    return std::get_if<csg::AlgebraicSurface>(&r.model->root->primitive);
}

TEST(IoSurface, SphereAsSurfaceProbesLikeSphere) {
    // Radius 2 about (1, 0, 0) written three ways the parser must read identically; seeded rays
    // from outside aimed near the centre (so most hit, some graze, some miss), judged by the
    // sphere's own formula here (not by csgray's sphere()): |o + t d - c|^2 = 4 with |d| = 1
    // gives t = b - sqrt(b^2 - |o - c|^2 + 4), b = d . (c - o), in long double.
    const csg::Vec3 c(1.0, 0.0, 0.0);
    for (const char* f :
         {"x^2 + y^2 + z^2 - 4", "(x*x + y*y + z*z) / 4 - 1", "-(4 - x^2 - y*y - z^2)"}) {
        const csg::Scene s = scene(std::string("translate([1, 0, 0]) surface(f = \"") + f +
                                   "\", bbox = [[-3, -3, -3], [3, 3, 3]]);");
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        csg::QueryContext ctx;
        int hits = 0, grazing = 0;
        for (int i = 0; i < 2000; ++i) {
            const csg::Vec3 o = 10.0 * glm::normalize(csg::Vec3(u(rng), u(rng), u(rng)));
            const csg::Vec3 target(1 + 2.2 * u(rng), 2.2 * u(rng), 2.2 * u(rng));
            const csg::Ray ray{o, glm::normalize(target - o), 0.0, csg::kInfinity};
            long double b = 0.0L, oc2 = 0.0L;
            for (int a = 0; a < 3; ++a) {
                b += (long double)ray.d[a] * ((long double)c[a] - o[a]);
                oc2 += ((long double)o[a] - c[a]) * ((long double)o[a] - c[a]);
            }
            const long double disc = b * b - oc2 + 4.0L;
            // Tolerance: the surface's quadratic has coefficients ~|o - c|^2 = ~100, so its
            // roots move by ~u 100 / |p'(t)| with |p'(t)| = 2 sqrt(disc) (u = 2^-53): below
            // 1e-11 where disc > 1e-6. Rays grazing closer than that are skipped (a handful).
            if (std::abs(disc) < 1e-6L) {
                ++grazing;
                continue;
            }
            const auto hit = s.closest(ray, ctx);
            ASSERT_EQ(hit.has_value(), disc > 0) << f << " ray " << i;
            if (!hit) continue;
            ++hits;
            const double t = double(b - std::sqrt(disc));
            EXPECT_NEAR(hit->t, t, 1e-9) << f;
            const csg::Vec3 normal = (o + t * ray.d - c) / 2.0;
            EXPECT_NEAR(glm::dot(s.surface(ray, *hit).normal, normal), 1.0, 1e-9) << f;
        }
        EXPECT_GT(hits, 500) << f;
        EXPECT_LE(grazing, 5) << f;
        EXPECT_TRUE(s.inside(csg::Vec3(1, 0, 0)));
        EXPECT_FALSE(s.inside(csg::Vec3(1, 2.01, 0)));
    }
}

TEST(IoSurface, SolverAndToleranceReachThePrimitive) {
    for (csg::Solver solver : csg::kAllSolvers) {
        EvaluateResult r = run(std::string("surface(\"x^4 + y^4 + z^4 - 1\", [[-2, -2, -2], "
                                           "[2, 2, 2]], \"") +
                               csg::solverName(solver) + "\", tolerance = 1e-6);");
        const csg::AlgebraicSurface* a = surfaceOf(r);
        ASSERT_NE(a, nullptr) << csg::solverName(solver);
        EXPECT_EQ(a->solver, solver);
        EXPECT_EQ(a->tolerance, 1e-6);
    }
    const csg::AlgebraicSurface* a =
        surfaceOf(run("surface(f = \"x + y + z\", bbox = "
                      "[[0, 0, 0], [1, 1, 1]], $fn = 3);"));
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->solver, csg::Solver::Auto);
}

TEST(IoSurface, DegreeSixteenIsAcceptedSeventeenIsNot) {
    EXPECT_NE(surfaceOf(run("surface(f = \"(x^2 + y^2 + z^2 - 1)^8\", "
                            "bbox = [[-2, -2, -2], [2, 2, 2]]);")),
              nullptr);
    EXPECT_EQ(error("surface(f = \"x^17 - 1\", bbox = [[-2, -2, -2], [2, 2, 2]]);"),
              "test.scad:1:15: error: surface(): f has degree above 16 here (the most csgray "
              "solves)");
    EXPECT_EQ(error("surface(f = \"x^9 * y^8\", bbox = [[-2, -2, -2], [2, 2, 2]]);"),
              "test.scad:1:18: error: surface(): f has degree above 16 here (the most csgray "
              "solves)");
}

TEST(IoSurface, LongSumsExpandButDeepRightNestingIsRefused) {
    // A fully expanded polynomial is a long flat sum: a tall tree that holds one operand.
    std::string sum = "x^2 + y^2 + z^2 - 4";
    for (int i = 0; i < 2000; ++i) sum += " + 0*x*y";
    EXPECT_NE(surfaceOf(run("surface(f = \"" + sum + "\", bbox = [[-3, -3, -3], [3, 3, 3]]);")),
              nullptr);
    // Right nesting holds an operand per level (79 KB each): bounded, with a located error.
    std::string nested = "x";
    for (int i = 0; i < 70; ++i) nested = "1 + (" + nested + ")";
    const std::string e =
        error("surface(f = \"" + nested + "\", bbox = [[-1, -1, -1], [1, 1, 1]]);");
    EXPECT_NE(e.find("error: surface(): f nests more than 64 operands deep"), std::string::npos)
        << e;
}

TEST(IoSurface, NonPolynomialFIsLocatedInsideTheString) {
    const std::string form =
        "; expected surface(f = \"polynomial in x, y, z\", bbox = [[x0, y0, "
        "z0], [x1, y1, z1]], solver = \"auto\", tolerance = 0, polish = \"auto\")";
    const std::string box = ", bbox = [[-1, -1, -1], [1, 1, 1]]);";
    // The quote is at column 13, so f's first character is column 14.
    EXPECT_EQ(error("surface(f = \"x^2 + sin(y) - 1\"" + box),
              "test.scad:1:20: error: surface(): f is not a polynomial: 'sin'" + form);
    EXPECT_EQ(error("cube();\nsurface(f = \"x^2 + a\"" + box),
              "test.scad:2:20: error: surface(): f is not a polynomial: 'a' (only x, y, z and "
              "numbers may appear)" +
                  form);
    EXPECT_EQ(error("surface(f = \"x / y\"" + box),
              "test.scad:1:18: error: surface(): f is not a polynomial: division by a "
              "polynomial" +
                  form);
    EXPECT_EQ(error("surface(f = \"x^0.5\"" + box),
              "test.scad:1:16: error: surface(): f is not a polynomial: the exponent 0.5 (a "
              "polynomial's exponent is a whole number >= 0)" +
                  form);
    EXPECT_EQ(error("surface(f = \"x < 1\"" + box),
              "test.scad:1:16: error: surface(): f is not a polynomial: the operator '<'" + form);
    // A syntax error inside f, and an f that is not a literal (located at the argument).
    const std::string bad = error("surface(f = \"x^2 + * 3\"" + box);
    EXPECT_EQ(bad.rfind("test.scad:1:20: error: surface(): f is not an expression:", 0), 0u) << bad;
    const std::string viaVariable = error("g = \"cos(x)\";\nsurface(f = g" + box);
    EXPECT_EQ(viaVariable,
              "test.scad:2:9: error: surface(): f is not a polynomial: 'cos' (at line 1, column "
              "1 of f)" +
                  form);
    EXPECT_EQ(error("surface(f = 3" + box)
                  .rfind("test.scad:1:9: error: surface(): 'f' must be a "
                         "string, got 3",
                         0),
              0u);
    EXPECT_EQ(error("surface(bbox = [[-1, -1, -1], [1, 1, 1]]);"),
              "test.scad:1:1: error: surface() needs a polynomial f" + form);
    // file = ... is OpenSCAD's heightmap (io/HeightmapModule.h): a missing file is an error at it.
    EXPECT_EQ(error("surface(file = \"h.png\");").rfind("test.scad:1:9: error: surface(): ", 0),
              0u);
}

TEST(IoSurface, BadBoxAndUnknownSolverAreLocated) {
    const std::string f = "surface(f = \"x^2 + y^2 + z^2 - 1\", ";
    const std::string boxForm =
        "'bbox' must be [[x0, y0, z0], [x1, y1, z1]] with x0 < x1, y0 < "
        "y1, z0 < z1, got ";
    EXPECT_EQ(error(f + "bbox = [[1, -1, -1], [-1, 1, 1]]);")
                  .rfind("test.scad:1:36: error: surface(): " + boxForm, 0),
              0u);
    EXPECT_EQ(error(f + "bbox = [1, 2]);").rfind("test.scad:1:36: error: surface(): " + boxForm, 0),
              0u);
    EXPECT_EQ(error(f + "bbox = [[0, 0], [1, 1]]);")
                  .rfind("test.scad:1:36: error: surface(): " + boxForm, 0),
              0u);
    EXPECT_EQ(error("surface(f = \"x\");")
                  .rfind("test.scad:1:1: error: surface() needs a "
                         "bounding box bbox",
                         0),
              0u);
    EXPECT_EQ(error(f + "bbox = [[-1, -1, -1], [1, 1, 1]], solver = \"newton\");"),
              "test.scad:1:70: error: surface(): unknown solver \"newton\"; expected one of "
              "\"auto\", \"closed-form\", \"sturm-bisection\", \"sturm-illinois\", \"yuksel\", "
              "\"descartes\", \"bernstein\", \"interval\"");
    EXPECT_EQ(error(f + "bbox = [[-1, -1, -1], [1, 1, 1]], polish = \"halley\");"),
              "test.scad:1:70: error: surface(): unknown polish \"halley\"; expected one of "
              "\"auto\", \"none\", \"newton\", \"laguerre\", \"bairstow\"");
}

}  // namespace
