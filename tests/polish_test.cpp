// Tests of root polishing (primitives/solvers/Polish.h): a simple root comes back within one
// ulp of the exact root of the polynomial of the double inputs, against references computed in
// 50 digits (Boost.Multiprecision, rootref::realRoots) from those inputs alone: for solve(), the
// double coefficients; for a surface, its stored double coefficients G, its centre and the
// ray's doubles o, d, expanded term by term (rootref::trivariateLine); for a torus, R, r, o and
// d (rootref::torusQuartic). RootReference.h uses nothing of primitives/solvers/.
//
// Notation: ulps(t, ref) = |t - ref| / ulp(ref) with ref the 50-digit root; the double nearest
// to ref is within 0.5, "within an ulp" is <= 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "primitives/AlgebraicSurface.h"
#include "primitives/Torus.h"
#include "primitives/solvers/Polish.h"
#include "primitives/solvers/Solve.h"
#include "primitives/solvers/reference/RootReference.h"
#include "primitives/solvers/reference/ShellSurface.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

using rootref::Big;
using testing::Rng;

double ulps(double t, const Big& ref) {
    const double r = ref.convert_to<double>();
    return (abs(Big(t) - ref) / Big(ulpOf(r))).convert_to<double>();
}

// What one configuration did on a set of rays: the largest ulp error over the roots matched,
// the share of roots that are the double nearest the reference, and the rays whose root count
// differs from the reference's.
struct Tally {
    double maxUlps = 0.0;
    long roots = 0, nearest = 0, countMismatches = 0;
    void add(const std::vector<double>& got, const std::vector<Big>& want) {
        if (got.size() != want.size()) {
            ++countMismatches;
            return;
        }
        for (size_t i = 0; i < got.size(); ++i) {
            const double e = ulps(got[i], want[i]);
            maxUlps = std::max(maxUlps, e);
            ++roots;
            nearest += got[i] == want[i].convert_to<double>() ? 1 : 0;
        }
    }
    void print(const char* what) const {
        std::printf("%-44s roots %6ld  max %10.3g ulps  nearest %6.2f %%  count mismatches %ld\n",
                    what, roots, maxUlps, 100.0 * double(nearest) / double(std::max(1L, roots)),
                    countMismatches);
    }
};

// ---- Surfaces: G(o - centre + t d) in 50 digits from G's double coefficients ----

std::vector<Big> multiply(const std::vector<Big>& a, const std::vector<Big>& b) {
    std::vector<Big> out(a.size() + b.size() - 1, Big(0));
    for (size_t i = 0; i < a.size(); ++i)
        for (size_t k = 0; k < b.size(); ++k) out[i + k] += a[i] * b[k];
    return out;
}

// The surface crossings of spans() (ends on face 6), ascending.
std::vector<double> surfaceEnds(const AlgebraicSurface& s, const Vec3& o, const Vec3& d) {
    LocalSpans spans;
    s.spans(o, d, spans);
    std::vector<double> out;
    for (int i = 0; i < spans.count; ++i) {
        if (spans.entries[i].faceIn == AlgebraicSurface::kSurfaceFace)
            out.push_back(spans.entries[i].tIn);
        if (spans.entries[i].faceOut == AlgebraicSurface::kSurfaceFace)
            out.push_back(spans.entries[i].tOut);
    }
    return out;
}

struct Line {
    Vec3 o, d;
    std::vector<Big> roots;  // the reference, within the chord
};

// Lines from 4 units away through random points of the ball of radius `aim`, with their
// reference roots inside the box.
std::vector<Line> surfaceLines(const AlgebraicSurface& s, int count, uint64_t seed, double aim) {
    Rng rng(seed);
    std::vector<Line> out;
    while (int(out.size()) < count) {
        const Vec3 o = 4.0 * glm::normalize(rng.inBall());
        const Vec3 d = aim * rng.inBall() - o;
        AlgebraicSurface::Chord c;
        if (!s.chord(o, d, c)) continue;
        out.push_back({o, d,
                       rootref::realRoots(rootref::trivariateLine(s.data->g, s.data->centre, o, d),
                                          Big(c.tIn), Big(c.tOut))});
    }
    return out;
}

Tally surfaceTally(AlgebraicSurface s, Polisher polisher, const std::vector<Line>& lines) {
    s.polisher = polisher;
    Tally t;
    for (const Line& l : lines) t.add(surfaceEnds(s, l.o, l.d), l.roots);
    return t;
}

AlgebraicSurface closeShells() {
    const ExactPolynomial x = ExactPolynomial::x(), y = ExactPolynomial::y(),
                          z = ExactPolynomial::z();
    const ExactPolynomial r2 = *x.times(x) + *y.times(y) + *z.times(z);
    const ExactPolynomial f =
        *(r2 - ExactPolynomial::constant(1.0)).times(r2 - ExactPolynomial::constant(1.000001));
    return AlgebraicSurface::make(f, {Vec3(-2.0), Vec3(2.0)});
}

// Issue 23: the shells 5e-7 apart, (x^2+y^2+z^2-1)(x^2+y^2+z^2-1.000001). Their chord
// polynomial's roots are ill-conditioned (|p'| ~ 1e-6 at each), so the isolating solver's
// double roots are ~1e-10 off; polished, every crossing is within an ulp, by every polisher.
TEST(Polish, CloseShellsCrossingsWithinAnUlp) {
    const AlgebraicSurface s = closeShells();
    const std::vector<Line> lines = surfaceLines(s, 1500, 2301, 0.99);
    const Tally none = surfaceTally(s, Polisher::None, lines);
    none.print("close shells, polish none");
    EXPECT_GT(none.maxUlps, 1e3) << "the case no longer needs polishing";
    for (Polisher p : {Polisher::Auto, Polisher::Newton, Polisher::Laguerre, Polisher::Bairstow}) {
        const Tally t = surfaceTally(s, p, lines);
        t.print((std::string("close shells, polish ") + polisherName(p)).c_str());
        EXPECT_LE(t.maxUlps, 1.0) << polisherName(p);
        EXPECT_EQ(t.countMismatches, 0) << polisherName(p);
        EXPECT_GT(t.roots, 5000) << polisherName(p);
    }
}

// The accuracy report's shells (2 and 4 origin-centred spheres, radii^2 0.25 .. 1.4).
TEST(Polish, ReportShellsCrossingsWithinAnUlp) {
    for (int degree : {4, 8}) {
        const AlgebraicSurface s = shellSurface(degree);
        const std::vector<Line> lines = surfaceLines(s, degree == 4 ? 1000 : 300, 2302, 1.5);
        for (Polisher p : {Polisher::None, Polisher::Auto, Polisher::Newton, Polisher::Laguerre,
                           Polisher::Bairstow}) {
            const Tally t = surfaceTally(s, p, lines);
            char what[64];
            std::snprintf(what, sizeof what, "shells %d, polish %s", degree, polisherName(p));
            t.print(what);
            EXPECT_EQ(t.countMismatches, 0) << what;
            if (p != Polisher::None) {
                EXPECT_LE(t.maxUlps, 1.0) << what;
            }
        }
    }
}

// ---- Tori: the quartic of the line's doubles (rootref::torusQuartic) ----

TEST(Polish, TorusCrossingsWithinAnUlp) {
    for (const double r : {0.25, 1e-3}) {
        Torus torus{1.0, r};
        Rng rng(2303);
        std::vector<Line> lines;
        while (lines.size() < 1500) {
            const Vec3 o = 3.0 * glm::normalize(rng.inBall());
            // Aimed at points near the tube's centre circle so that most lines cross it.
            const double phi = rng.uniform(0.0, 6.283185307179586);
            const Vec3 ball = rng.inBall();
            const Vec3 aim = Vec3(std::cos(phi), std::sin(phi), 0.0) + 1.5 * r * ball;
            const Vec3 d = aim - o;
            std::vector<Big> roots =
                rootref::realRoots(rootref::torusQuartic(1.0, r, o, d), Big(-100), Big(100));
            // Lines with roots closer than 1e-4 r are tangent to rounding (torus_test's rule).
            bool separated = true;
            for (size_t i = 0; i + 1 < roots.size(); ++i)
                separated = separated && roots[i + 1] - roots[i] > 1e-4 * r;
            if (separated) lines.push_back({o, d, roots});
        }
        for (Solver solver : {Solver::Auto, Solver::ClosedForm})
            for (Polisher p : {Polisher::None, Polisher::Auto, Polisher::Newton, Polisher::Laguerre,
                               Polisher::Bairstow}) {
                torus.solver = solver;
                torus.polisher = p;
                Tally t;
                for (const Line& l : lines) {
                    LocalSpans spans;
                    torus.spans(l.o, l.d, spans);
                    std::vector<double> ends;
                    for (int i = 0; i < spans.count; ++i)
                        ends.push_back(spans.entries[i].tIn), ends.push_back(spans.entries[i].tOut);
                    t.add(ends, l.roots);
                }
                char what[80];
                std::snprintf(what, sizeof what, "torus r = %g, %s, polish %s", r,
                              solver == Solver::Auto ? "tube" : "quartic", polisherName(p));
                t.print(what);
                EXPECT_EQ(t.countMismatches, 0) << what;
                if (p != Polisher::None) {
                    EXPECT_LE(t.maxUlps, 1.0) << what;
                }
            }
    }
}

// ---- Polynomials given by their double coefficients: the report's hard quartics ----

// Roots expanded in 50 digits, rounded once to double coefficients.
Polynomial fromRoots(const std::vector<double>& roots) {
    std::vector<Big> c = {Big(1)};
    for (double r : roots) c = multiply(c, {Big(-r), Big(1)});
    Polynomial p = Polynomial::ofDegree(int(c.size()) - 1);
    for (size_t i = 0; i < c.size(); ++i) p[int(i)] = c[i].convert_to<double>();
    return p;
}

// The accuracy report's degree-4 classes (AccuracyReport.cpp), drawn here with the test Rng:
// Flocke's decimal cluster (2 + s + k / 1000), a pair 1e-5 apart among two others, and roots
// over seven decades.
std::vector<Polynomial> hardQuartics(int perClass) {
    Rng rng(2304);
    std::vector<Polynomial> out;
    for (int i = 0; i < perClass; ++i) {
        const double s = rng.uniform(-1.0, 1.0);
        std::vector<double> roots;
        int used = 0;
        while (roots.size() < 4) {
            const int k = rng.index(8);
            if (used & (1 << k)) continue;
            used |= 1 << k;
            roots.push_back(2.0 + s + k / 1000.0);
        }
        out.push_back(fromRoots(roots));
    }
    while (int(out.size()) < 2 * perClass) {
        const double a = rng.uniform(-3.0, 3.0), b = rng.uniform(-3.0, 3.0),
                     c = rng.uniform(-3.0, 3.0);
        if (std::abs(a - b) < 0.1 || std::abs(a - c) < 0.1 || std::abs(b - c) < 0.1) continue;
        out.push_back(fromRoots({a, a + 1e-5, b, c}));
    }
    while (int(out.size()) < 3 * perClass) {
        std::vector<double> roots;
        for (int i = 0; i < 4; ++i) {
            const double sign = rng.chance(0.5) ? 1.0 : -1.0;
            const double decade = rng.uniform(-3.0, 4.0);
            roots.push_back(sign * std::pow(10.0, decade));
        }
        std::sort(roots.begin(), roots.end());
        bool ok = true;
        for (size_t i = 1; i < roots.size(); ++i)
            ok = ok && roots[i] - roots[i - 1] > 1e-3 * std::abs(roots[i]);
        if (ok) out.push_back(fromRoots(roots));
    }
    return out;
}

TEST(Polish, HardQuarticRootsWithinAnUlp) {
    const std::vector<Polynomial> quartics = hardQuartics(700);
    std::vector<std::vector<Big>> want;
    for (const Polynomial& p : quartics) {
        std::vector<Big> c;
        for (int i = 0; i <= p.degree(); ++i) c.push_back(Big(p[i]));
        want.push_back(rootref::realRoots(c, Big(-2e4), Big(2e4)));
    }
    for (Polisher polisher : {Polisher::None, Polisher::Auto, Polisher::Newton, Polisher::Laguerre,
                              Polisher::Bairstow}) {
        Tally t;
        for (size_t k = 0; k < quartics.size(); ++k) {
            double roots[Polynomial::kMaxDegree];
            const int n = solve(quartics[k], -2e4, 2e4, roots, Solver::Auto, 0.0, polisher);
            t.add(std::vector<double>(roots, roots + n), want[k]);
        }
        t.print((std::string("hard quartics, polish ") + polisherName(polisher)).c_str());
        // The decimal clusters hold rays double cannot resolve (the accuracy report counts
        // them); the roots of every ray it does resolve are compared.
        EXPECT_LE(t.countMismatches, 20) << polisherName(polisher);
        if (polisher != Polisher::None) {
            EXPECT_LE(t.maxUlps, 1.0) << polisherName(polisher);
        }
    }
}

// Each polisher on its own, from a start a million ulps off, on polynomials whose roots are
// exact doubles (dyadic, coefficients exact): it returns the root itself.
TEST(Polish, EachPolisherConvergesToTheExactDouble) {
    const double roots[] = {-1.75, 0.375, 0.5, 3.25, 5.125};
    std::vector<Big> c = {Big(1)};
    for (double r : roots) c = multiply(c, {Big(-r), Big(1)});
    Polynomial p = Polynomial::ofDegree(5);
    for (int i = 0; i <= 5; ++i) p[i] = c[size_t(i)].convert_to<double>();
    const PolynomialDD dd(p);
    for (Polisher m : {Polisher::Newton, Polisher::Laguerre, Polisher::Bairstow})
        for (int i = 0; i < 5; ++i) {
            double start[5];
            for (int k = 0; k < 5; ++k) start[k] = roots[k] * (1.0 + 1e-10);
            double lo, hi;
            rootBracket(start, 5, i, -10.0, 10.0, &lo, &hi);
            EXPECT_EQ(polishRootWith(m, dd, start, 5, i, lo, hi).value(), roots[i])
                << polisherName(m) << " root " << roots[i];
        }
}

}  // namespace
}  // namespace csg
