// Tests of the real-root solvers (primitives/solvers/) against a reference that is exact.
//
// The reference: every test polynomial is built from roots we choose, and its coefficients are
// expanded in 50-digit arithmetic (Boost.Multiprecision cpp_bin_float_50). For the random
// classes, roots are dyadic with few bits, and a polynomial is kept only when every expanded
// coefficient is exactly a double: then the double polynomial the solvers see *is* the chosen
// one and its roots, with multiplicity, are known exactly. For the published hard quartics,
// whose decimal roots are not dyadic, the coefficients are rounded to double and the reference
// roots are the chosen ones polished by Newton in 50 digits on the rounded coefficients.
//
// Notation: a reference is a list of roots in the solvers' contract (Solve.h): a crossing
// listed once, a tangency twice. error = |root - reference| / max(1, |reference|).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "primitives/solvers/Polynomial.h"
#include "primitives/solvers/Solve.h"
#include "tests/EnvCount.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

using Big = boost::multiprecision::cpp_bin_float_50;

// ---- Building polynomials from roots in 50 digits ----

// Multiplies the ascending coefficient list by (t^2 + b t + c).
void multiplyBy(std::vector<Big>& c, const Big& b1, const Big& b0, bool quadratic) {
    std::vector<Big> out(c.size() + (quadratic ? 2 : 1), Big(0));
    for (size_t i = 0; i < c.size(); ++i) {
        out[i] += c[i] * b0;
        out[i + 1] += c[i] * b1;
        if (quadratic) out[i + 2] += c[i];
    }
    c = out;
}

struct Roots {
    std::vector<double> real;                        // with repetition = multiplicity
    std::vector<std::pair<double, double>> complex;  // (re, im > 0): one conjugate pair each
};

std::vector<Big> expand(const Roots& r) {
    std::vector<Big> c{Big(1)};
    for (double x : r.real) multiplyBy(c, Big(1), -Big(x), false);
    for (auto [re, im] : r.complex)
        multiplyBy(c, -2 * Big(re), Big(re) * Big(re) + Big(im) * Big(im), true);
    return c;
}

// The double polynomial; *exact says whether rounding changed any coefficient.
Polynomial toDouble(const std::vector<Big>& c, bool* exact) {
    Polynomial p = Polynomial::ofDegree(int(c.size()) - 1);
    *exact = true;
    for (size_t i = 0; i < c.size(); ++i) {
        p[int(i)] = double(c[i]);
        if (Big(p[int(i)]) != c[i]) *exact = false;
    }
    return p;
}

// The contract's listing of exact roots: multiplicity m becomes 1 (odd) or 2 (even) entries.
std::vector<double> contractListing(std::vector<double> real) {
    std::sort(real.begin(), real.end());
    std::vector<double> out;
    for (size_t i = 0; i < real.size();) {
        size_t j = i;
        while (j < real.size() && real[j] == real[i]) ++j;
        out.push_back(real[i]);
        if ((j - i) % 2 == 0) out.push_back(real[i]);
        i = j;
    }
    return out;
}

// Newton in 50 digits on the double coefficients of p, from x.
double polishBig(const Polynomial& p, double x) {
    Big t(x);
    for (int it = 0; it < 100; ++it) {
        Big v(p[p.degree()]), dv(0);
        for (int i = p.degree() - 1; i >= 0; --i) {
            dv = dv * t + v;
            v = v * t + Big(p[i]);
        }
        if (dv == 0) break;
        const Big step = v / dv;
        t -= step;
        if (abs(step) <= abs(t) * Big(1e-45)) break;
    }
    return double(t);
}

// ---- Comparing a solver's answer to the reference ----

struct Tally {
    uint64_t cases = 0, wrongCount = 0;
    double maxError = 0.0;
    double maxLimitRatio = 0.0;  // max of |error| / conditioningLimit
};

double rootError(double got, double want) {
    return std::abs(got - want) / std::max(1.0, std::abs(want));
}

// What double precision allows for a root r of p: p's rounding bound at r moves a simple root
// by bound / |p'(r)| (first order) and a tangency by sqrt(2 bound / |p''(r)|); add 2 ulps of r
// for the root's own rounding. Unit: t.
double conditioningLimit(const Polynomial& p, double r, bool tangency) {
    double bound;
    p.eval(r, &bound);
    const double slack = 2.0 * tol::kUlp * std::abs(r) + 1e-300;
    if (!tangency) return slack + bound / std::abs(p.derivative()(r));
    return slack + std::sqrt(2.0 * bound / std::abs(p.derivative().derivative()(r)));
}

// Updates the tally; returns false on a wrong count.
bool compare(const Polynomial& p, const std::vector<double>& want, const double* got, int n,
             Tally& t) {
    ++t.cases;
    if (n != int(want.size())) {
        ++t.wrongCount;
        return false;
    }
    for (int i = 0; i < n; ++i) {
        t.maxError = std::max(t.maxError, rootError(got[i], want[i]));
        const bool tangency =
            (i > 0 && want[i - 1] == want[i]) || (i + 1 < n && want[i + 1] == want[i]);
        const double limit = conditioningLimit(p, want[i], tangency);
        t.maxLimitRatio = std::max(t.maxLimitRatio, std::abs(got[i] - want[i]) / limit);
    }
    return true;
}

// ---- Random classes with exact dyadic roots ----

using testing::Rng;

// k / 2^denominatorLog2 for k in lo .. hi.
double dyadic(Rng& rng, int lo, int hi, int denominatorLog2) {
    return std::ldexp(double(rng.integer(lo, hi)), -denominatorLog2);
}

struct Case {
    Polynomial p;
    std::vector<double> want;
    double tlo, thi;
};

// Roots on the grid k / 256 in [-4, 4], at least `gap` apart.
double separatedRoot(Rng& rng, const std::vector<double>& others, double gap) {
    for (;;) {
        const double x = dyadic(rng, -1024, 1024, 8);
        bool ok = true;
        for (double o : others) ok = ok && std::abs(x - o) >= gap;
        if (ok) return x;
    }
}

using Generator = Roots (*)(Rng&, int degree);

Roots separated(Rng& rng, int degree) {
    Roots r;
    for (int i = 0; i < degree; ++i) r.real.push_back(separatedRoot(rng, r.real, 1.0 / 64));
    return r;
}
Roots withComplexPair(Rng& rng, int degree) {
    Roots r;
    for (int i = 0; i < degree - 2; ++i) r.real.push_back(separatedRoot(rng, r.real, 1.0 / 64));
    r.complex.push_back({dyadic(rng, -1024, 1024, 8), dyadic(rng, 4, 512, 8)});
    return r;
}
Roots allComplex(Rng& rng, int degree) {
    Roots r;
    for (int i = 0; i < degree / 2; ++i)
        r.complex.push_back({dyadic(rng, -1024, 1024, 8), dyadic(rng, 4, 512, 8)});
    if (degree % 2) r.real.push_back(dyadic(rng, -1024, 1024, 8));
    return r;
}
// Flocke's cluster {2.000, 2.001, 2.002, 2.003} on a dyadic grid: 2 + k / 512, k distinct.
Roots cluster(Rng& rng, int degree) {
    Roots r;
    while (int(r.real.size()) < degree) {
        const double x = 2.0 + dyadic(rng, 0, 8, 9);
        if (std::find(r.real.begin(), r.real.end(), x) == r.real.end()) r.real.push_back(x);
    }
    return r;
}
// One exact double root (a tangent ray) and the rest separated.
Roots tangent(Rng& rng, int degree) {
    Roots r;
    const double x = dyadic(rng, -1024, 1024, 8);
    r.real = {x, x};
    for (int i = 2; i < degree; ++i) r.real.push_back(separatedRoot(rng, r.real, 1.0 / 64));
    return r;
}
// Roots spread over 2^-12 .. 2^12 (seven decades), 6 significant bits each.
Roots wideRange(Rng& rng, int degree) {
    Roots r;
    while (int(r.real.size()) < degree) {
        const int exponent = rng.integer(-17, 7);  // drawn first, as gcc did
        const double x = std::ldexp(double(rng.integer(32, 63)), exponent);
        const double s = rng.integer(0, 1) ? x : -x;
        if (std::find(r.real.begin(), r.real.end(), s) == r.real.end()) r.real.push_back(s);
    }
    return r;
}

Case exactCase(Rng& rng, Generator gen, int degree) {
    for (;;) {
        const Roots r = gen(rng, degree);
        bool exact;
        const Polynomial p = toDouble(expand(r), &exact);
        if (!exact) continue;  // the double polynomial would not be the one we chose
        double hi = 0.0;
        for (double x : r.real) hi = std::max(hi, std::abs(x));
        for (auto [re, im] : r.complex) hi = std::max(hi, std::abs(re) + im);
        hi = 2.0 * hi + 1.0;
        return {p, contractListing(r.real), -hi, hi};
    }
}

struct ClassSpec {
    const char* name;
    Generator gen;
    int degree;
};

// Auto's roots must lie within this many conditioning limits (see conditioningLimit) of the
// exact ones: the limit is the displacement that p's own rounding causes, so a solver that
// stops when |p| reaches its rounding noise lands within one or two of them.
constexpr double kAutoLimitRatio = 4.0;

// What every solver is held to in the random classes: its roots within kAutoLimitRatio
// conditioning limits, and at most this fraction of cases with a wrong count. Auto, the
// closed form, Yuksel and Descartes are right on every case (bench/reports/accuracy.md: 0 wrong
// at rel_tol 0 on every class); Bernstein, interval and the Sturm solvers lose a root on a few
// cases in 10^5 (the report: Bernstein 1-3 / 1000 at degrees 15-16, interval 4 / 2000 on
// near-doubles, Sturm 7 / 2000 on shells of degree 16), held here to 1e-4.
double wrongFractionAllowed(Solver solver) {
    switch (solver) {
        case Solver::Bernstein:
        case Solver::Interval:
        case Solver::SturmBisection:
        case Solver::SturmIllinois:
            return 1e-4;
        default:
            return 0.0;
    }
}

// Sturm isolation counts sign changes, so it cannot see a tangency (an even root, no sign
// change): on the tangent classes it breaks Solve.h's contract (a tangency listed twice) on
// ~90 % of cases. Exempt there, and said so; everywhere else it is held like the others.
bool missesTangencies(Solver solver) {
    return solver == Solver::SturmBisection || solver == Solver::SturmIllinois;
}

const ClassSpec kClasses[] = {
    {"cubic-separated", separated, 3},
    {"cubic-tangent", tangent, 3},
    {"cubic-complex", withComplexPair, 3},
    {"quartic-separated", separated, 4},
    {"quartic-complex-pair", withComplexPair, 4},
    {"quartic-no-real", allComplex, 4},
    {"quartic-cluster", cluster, 4},
    {"quartic-tangent", tangent, 4},
    {"quartic-wide-range", wideRange, 4},
    {"sextic-separated", separated, 6},
    {"octic-separated", separated, 8},
};

// 1e5 per class by default (the issue's floor); CSGRAY_SOLVER_CASES=N overrides it, for a quick
// run while working on one solver or for a larger sweep.
int randomPerClass() {
    return csg::testing::countFromEnv("CSGRAY_SOLVER_CASES", 100000);
}

TEST(Solvers, RandomClassesAgainstExactReference) {
    std::printf("%-22s %-16s %8s %8s %11s %11s %9s\n", "class", "solver", "cases", "wrong#",
                "max error", "err/limit", "ns/poly");
    for (const ClassSpec& spec : kClasses) {
        Rng rng(0x5eed0000u + uint64_t(spec.degree) * 131 + uint64_t(spec.name[0]));
        std::vector<Case> cases;
        const int perClass = randomPerClass();
        cases.reserve(perClass);
        for (int i = 0; i < perClass; ++i) cases.push_back(exactCase(rng, spec.gen, spec.degree));
        for (Solver solver : kAllSolvers) {
            Tally tally;
            double roots[Polynomial::kMaxDegree];
            std::string firstWrong;
            const auto start = std::chrono::steady_clock::now();
            for (const Case& c : cases) {
                const int n = solve(c.p, c.tlo, c.thi, roots, solver);
                if (!compare(c.p, c.want, roots, n, tally) && firstWrong.empty()) {
                    char buf[256];
                    std::snprintf(buf, sizeof buf, "got %d roots, want %zu; p[0]=%.17g", n,
                                  c.want.size(), c.p[0]);
                    firstWrong = buf;
                }
            }
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::printf("%-22s %-16s %8llu %8llu %11.3g %11.3g %9.0f\n", spec.name,
                        solverName(solver), (unsigned long long)tally.cases,
                        (unsigned long long)tally.wrongCount, tally.maxError, tally.maxLimitRatio,
                        1e9 * seconds / double(tally.cases));
            if (std::strstr(spec.name, "tangent") != nullptr && missesTangencies(solver))
                continue;
            EXPECT_LE(double(tally.wrongCount), wrongFractionAllowed(solver) * tally.cases)
                << spec.name << " " << solverName(solver) << ": " << firstWrong;
            EXPECT_LE(tally.maxLimitRatio, kAutoLimitRatio) << spec.name << " " << solverName(solver);
        }
    }
}

// ---- The published hard quartics ----

struct HardQuartic {
    const char* name;
    Roots roots;
};

Case hardCase(const HardQuartic& h) {
    bool exact;
    const Polynomial p = toDouble(expand(h.roots), &exact);
    std::vector<double> want;
    if (exact) {
        want = contractListing(h.roots.real);
    } else {
        // Decimal roots: the double polynomial's roots are the chosen ones moved by the
        // coefficient rounding; 50-digit Newton finds them (all are simple and separated here).
        for (double x : h.roots.real) want.push_back(polishBig(p, x));
        std::sort(want.begin(), want.end());
    }
    // Cauchy's bound: every root lies within 1 + max |c_i / c_n|.
    double bound = 0.0;
    for (int i = 0; i < p.degree(); ++i) bound = std::max(bound, std::abs(p[i] / p.leading()));
    return {p, want, -(1.0 + bound), 1.0 + bound};
}

// From Flocke (ACM TOMS 954), Strobach and Orellana & De Michele (ACM TOMS 1010): roots over
// many decades, a tight cluster, multiple roots, and real roots next to complex pairs.
const HardQuartic kHardQuartics[] = {
    {"decades {1e9,1e6,1e3,1}", {{1e9, 1e6, 1e3, 1.0}, {}}},
    {"cluster {2.003,2.002,2.001,2}", {{2.003, 2.002, 2.001, 2.0}, {}}},
    {"quadruple root 1000", {{1000.0, 1000.0, 1000.0, 1000.0}, {}}},
    {"two double roots {1,1,-1,-1}", {{1.0, 1.0, -1.0, -1.0}, {}}},
    {"triple root and one", {{3.0, 3.0, 3.0, -5.0}, {}}},
    {"{1e53,1e50,1e49,1e47}", {{1e53, 1e50, 1e49, 1e47}, {}}},
    {"{1e14,2,1,-1}", {{1e14, 2.0, 1.0, -1.0}, {}}},
    {"{-2e7,1e7,1,-1}", {{-2e7, 1e7, 1.0, -1.0}, {}}},
    {"{1e7,-1e6} + 1+-i", {{1e7, -1e6}, {{1.0, 1.0}}}},
    {"{-7,-4} + -1e6+-1e5i", {{-7.0, -4.0}, {{-1e6, 1e5}}}},
    {"{1e8,11} + 1e3+-i", {{1e8, 11.0}, {{1e3, 1.0}}}},
    {"{1.003,1.002} + 1+-1e-3i", {{1.003, 1.002}, {{1.0, 1e-3}}}},
    {"1+-i, 2+-3i (no real)", {{}, {{1.0, 1.0}, {2.0, 3.0}}}},
    {"1e-3 +- 1e-9 i (near-double, complex)", {{5.0, -5.0}, {{1e-3, 1e-9}}}},
};

// The hard quartics a solver other than Auto and the closed form is known to get wrong, each
// with why; every other pair is asserted.
bool knownHardFailure(const std::string& name, Solver solver) {
    const bool sturm = solver == Solver::SturmBisection || solver == Solver::SturmIllinois;
    // Measured: Sturm isolation finds 1 of the quadruple root's 2 listings (no sign change)
    // and 2 of the four decades 1e47..1e53, and lists the near-double complex pair as four
    // real roots.
    if (sturm && (name == "quadruple root 1000" || name == "{1e53,1e50,1e49,1e47}" ||
                  name == "1e-3 +- 1e-9 i (near-double, complex)"))
        return true;
    // Measured: Descartes and interval subdivision give 2 and 0 of the 1e-3 cluster's 4 roots.
    if ((solver == Solver::Descartes || solver == Solver::Interval) &&
        name == "cluster {2.003,2.002,2.001,2}")
        return true;
    return false;
}

TEST(Solvers, PublishedHardQuartics) {
    for (const HardQuartic& h : kHardQuartics) {
        const Case c = hardCase(h);
        for (Solver solver : kAllSolvers) {
            double roots[Polynomial::kMaxDegree];
            const int n = solve(c.p, c.tlo, c.thi, roots, solver);
            Tally t;
            const bool countOk = compare(c.p, c.want, roots, n, t);
            std::printf("%-38s %-16s roots %d/%zu  max error %9.3g  err/limit %9.3g\n", h.name,
                        solverName(solver), n, c.want.size(), t.maxError, t.maxLimitRatio);
            if (knownHardFailure(h.name, solver)) continue;
            EXPECT_TRUE(countOk) << h.name << " " << solverName(solver);
            EXPECT_LE(t.maxLimitRatio, kAutoLimitRatio) << h.name << " " << solverName(solver);
        }
    }
}

// Issue 5: decimal four-root clusters near 3 (the accuracy report's `cluster` class, seed 23)
// that Auto once returned as one tangency: p between the roots is 2-8 times its rounding bound,
// so double resolves them, but the merge rule asked for 8. Coefficients as the report rounded
// them; roots from its 50-digit reference (critical points, then Newton, on these doubles).
struct ResolvableCluster {
    Polynomial p;
    double roots[4];
};
const ResolvableCluster kResolvableClusters[] = {
    {{80.857944524526857, -107.85792085685625, 53.952632395549543, -11.994736056070545, 1},
     {2.9971891657427556, 2.9981688089611911, 2.99919922684923, 3.0001788545173684}},
    {{76.245240774771901, -103.20947705920076, 52.391117489541813, -11.819883810995979, 1},
     {2.9534695773779416, 2.9544750962347921, 2.9554668109459685, 2.9564723264372761}},
    {{77.883157725380045, -104.86792761974513, 52.950865976132562, -11.882858071034658, 1},
     {2.9692177059955811, 2.9702050512861748, 2.9712239857871219, 2.97221132796578}},
    {{75.695602101791749, -102.65095837063542, 52.201936723496011, -11.798524113746431, 1},
     {2.9481329254559427, 2.9491253638956856, 2.9501367022221712, 2.9511291221726323}},
    {{80.276454988877546, -107.27565155273558, 53.758282312425365, -11.973112634835925, 1},
     {2.9917778908877803, 2.9927789699541973, 2.9937773404125645, 2.9947784335813821}},
    {{70.586666099511831, -97.409659712361304, 50.4095277073463, -11.594197423118894, 1},
     {2.8970482050116466, 2.8980528225230544, 2.8990458879436241, 2.9000505076405689}},
};

TEST(Solvers, ResolvableDecimalClustersAreFourCrossings) {
    for (const ResolvableCluster& c : kResolvableClusters) {
        const std::vector<double> want(c.roots, c.roots + 4);
        // The reference itself: each root is a sign change of p (50 digits), so it is right.
        for (double r : want) ASSERT_NEAR(polishBig(c.p, r), r, 1e-15 * r);
        for (Solver solver : {Solver::Auto, Solver::ClosedForm}) {
            double roots[Polynomial::kMaxDegree];
            const int n = solve(c.p, -5.0, 5.0, roots, solver);
            Tally t;
            EXPECT_TRUE(compare(c.p, want, roots, n, t))
                << solverName(solver) << ": " << n << " roots near " << want[0];
            EXPECT_LE(t.maxLimitRatio, kAutoLimitRatio) << solverName(solver);
        }
    }
}

// ---- Units ----

TEST(Solvers, RangeIsClosedAndOrdered) {
    // (t + 1) t (t - 1) (t - 2): only the roots in [0, 1] and ascending.
    const Polynomial p{0.0, 2.0, -1.0, -2.0, 1.0};
    for (Solver solver : kAllSolvers) {
        double r[4];
        ASSERT_EQ(solve(p, 0.0, 1.0, r, solver), 2) << solverName(solver);
        EXPECT_EQ(r[0], 0.0) << solverName(solver);
        EXPECT_EQ(r[1], 1.0) << solverName(solver);
    }
}

TEST(Solvers, TangencyIsListedTwice) {
    // (t - 3)^2 (t^2 + 1): one tangency at 3, nothing else.
    const Polynomial p{9.0, -6.0, 10.0, -6.0, 1.0};
    for (Solver solver : kAllSolvers) {
        double r[4];
        ASSERT_EQ(solve(p, -10.0, 10.0, r, solver), 2) << solverName(solver);
        EXPECT_NEAR(r[0], 3.0, 1e-7) << solverName(solver);
        EXPECT_EQ(r[0], r[1]) << solverName(solver);
    }
}

TEST(Solvers, HighDegreePowersOfASphere) {
    // (t^2 - 1)^k along a ray through a sphere's polynomial raised to the k-th power: roots
    // +-1 of multiplicity k, so tangencies for even k and crossings for odd k.
    for (int k = 2; k <= 8; ++k) {
        std::vector<Big> c{Big(1)};
        for (int i = 0; i < k; ++i) multiplyBy(c, Big(0), Big(-1), true);
        bool exact;
        const Polynomial p = toDouble(c, &exact);
        ASSERT_TRUE(exact);
        const int per = k % 2 ? 1 : 2;
        // The coefficients are exact, so only evaluation moves the roots: near t = 1,
        // p(t) ~ 2^k (t - 1)^k, and Horner's error is at most gamma(2n) sum |c_i| = ~4k u 2^k
        // (n = 2k, the binomial coefficients sum to 2^k, u = 2^-53). No solver can tell p
        // from 0 closer than |t - 1| = (4k u)^(1/k); twice that is the tolerance (8e-8 for
        // k = 2, 0.03 for k = 8).
        const double tolerance = 2.0 * std::pow(4.0 * k * std::ldexp(1.0, -53), 1.0 / k);
        for (Solver solver : {Solver::Auto, Solver::Yuksel, Solver::SturmIllinois}) {
            double r[Polynomial::kMaxDegree];
            const int n = solve(p, -4.0, 4.0, r, solver);
            EXPECT_EQ(n, 2 * per) << "k=" << k << " " << solverName(solver);
            if (n != 2 * per) continue;
            EXPECT_NEAR(r[0], -1.0, tolerance) << "k=" << k << " " << solverName(solver);
            EXPECT_NEAR(r[n - 1], 1.0, tolerance) << "k=" << k << " " << solverName(solver);
        }
    }
}

TEST(Polynomial, HornerBoundShiftAndDerivative) {
    const Polynomial p{-6.0, 11.0, -6.0, 1.0};  // (t-1)(t-2)(t-3)
    double bound;
    EXPECT_EQ(p.eval(2.0, &bound), 0.0);
    // Higham's a priori bound for Horner's rule with fma, gamma(2n) * sum |c_i| |t|^i
    // (Accuracy and Stability, 5.1), is what the running bound refines: here 6u * 60 with
    // u = 2^-53. The running bound may exceed it only by its own rounding, so allow twice.
    const double u = std::ldexp(1.0, -53), aPriori = 6 * u / (1 - 6 * u) * (6 + 22 + 24 + 8);
    EXPECT_LE(bound, 2.0 * aPriori);
    const Polynomial q = p.shifted(2.0);  // (t+1) t (t-1) = t^3 - t
    EXPECT_EQ(q[0], 0.0);
    EXPECT_EQ(q[1], -1.0);
    EXPECT_EQ(q[2], 0.0);
    EXPECT_EQ(q[3], 1.0);
    const Polynomial d = p.derivative();
    EXPECT_EQ(d.degree(), 2);
    EXPECT_EQ(d[0], 11.0);
    EXPECT_EQ(d[2], 3.0);
    const Polynomial s = p.argumentScaled(2.0);  // p(2t)
    EXPECT_EQ(s(0.5), p(1.0));
    // The running bound really bounds the error: compare with 50 digits at random points.
    Rng rng(7);
    const Polynomial w{1.1, -3.3, 2.7, -0.9, 0.1};
    for (int i = 0; i < 10000; ++i) {
        const double t = dyadic(rng, -4096, 4096, 10) + 1e-3 * rng.integer(0, 999);
        Big exact(0);
        for (int k = w.degree(); k >= 0; --k) exact = exact * Big(t) + Big(w[k]);
        const double got = w.eval(t, &bound);
        EXPECT_LE(double(abs(Big(got) - exact)), bound) << t;
        // Not vacuous: within twice the a priori bound gamma(2n) sum |c_i| |t|^i (n = 4).
        double magnitude = 0.0;
        for (int k = w.degree(); k >= 0; --k) magnitude = magnitude * std::abs(t) + std::abs(w[k]);
        EXPECT_LE(bound, 2.0 * 8 * u / (1 - 8 * u) * magnitude) << t;
    }
}

}  // namespace
}  // namespace csg
