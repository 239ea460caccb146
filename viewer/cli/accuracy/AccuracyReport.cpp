// What each digit of accuracy costs (AccuracyReport.h): for every root solver, surface class and
// tolerance setting, rays per second (solve() only) against the error distribution and the
// wrong root counts, measured on the polynomials that real rays produce.
//
// Notation: a job is one ray's polynomial p with its parameter range [lo, hi], exactly the
// doubles a solver is given. The reference is the set of real roots of that same double p,
// found in 50 digits (Boost.Multiprecision): so an error is the solver's own, not the
// rounding of p's coefficients (that part is the same for every solver). error = |root -
// reference| / max(1, |reference|); a ray whose root count differs from the reference's is a
// wrong count and has no error. Tangencies have probability zero in these classes. A wrong
// count is also reported as "resolvable" or not: on some rays (tight clusters) p between two
// roots is smaller than its own rounding error in double, so no double solver can see them.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "viewer/cli/accuracy/AccuracyReport.h"

#include "primitives/AlgebraicSurface.h"
#include "primitives/Torus.h"
#include "primitives/base/AtomicFile.h"
#include "primitives/solvers/reference/RootReference.h"
#include "primitives/solvers/reference/ScalarYuksel.h"
#include "primitives/solvers/reference/ShellSurface.h"
#include "viewer/cli/accuracy/AccuracyPlots.h"

namespace csg {
namespace {

using rootref::Big;

struct Job {
    Polynomial p;
    double lo, hi;
    std::vector<double> reference;  // the 50-digit roots rounded to double
    std::vector<Big> exact = {};    // the 50-digit roots themselves (errors in ulps)
    // False when p, between two adjacent reference roots, stays below its own rounding-error
    // bound in double (Polynomial::eval): no double evaluation can see the sign change
    // there, so a wrong count on this ray is double precision's limit, not the solver's.
    bool resolvable = true;
    // p's coefficients as float and as double arrays, for the float-vs-double rows.
    std::array<float, Polynomial::kMaxDegree + 1> pf{};
    std::array<double, Polynomial::kMaxDegree + 1> pd{};
    // A torus job's line b + s u (|u| = 1), whose quartic in s is p: what the tube row solves.
    Vec3 lineBase{}, lineDir{};
};

// ---- The 50-digit reference (RootReference.h) ----

void addReference(Job& j) {
    std::vector<Big> c(size_t(j.p.degree() + 1));
    for (int i = 0; i <= j.p.degree(); ++i) c[size_t(i)] = j.p[i];
    const std::vector<Big> roots = rootref::realRoots(c, Big(j.lo), Big(j.hi));
    for (const Big& r : roots) j.reference.push_back(r.convert_to<double>());
    j.exact = roots;
    for (int i = 0; i <= j.p.degree(); ++i)
        j.pf[size_t(i)] = float(j.p[i]), j.pd[size_t(i)] = j.p[i];
    for (size_t i = 0; i + 1 < roots.size(); ++i) {
        const Big mid = (roots[i] + roots[i + 1]) / 2;
        double bound = 0;
        j.p.eval(mid.convert_to<double>(), &bound);
        if (abs(rootref::evaluate(c, mid)) <= bound) j.resolvable = false;
    }
}

// ---- Surface classes ----

using Rng = std::mt19937_64;

Vec3 randomIn(Rng& g, double r) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (;;) {
        const Vec3 v(u(g), u(g), u(g));
        if (glm::dot(v, v) <= 1.0) return r * v;
    }
}

// The torus class's torus.
Torus reportTorus() {
    return Torus{1.0, 0.25};
}

// Rays from 4 units away through the torus R = 1, r = 0.25 (as solvers_bench and Torus.cpp
// solve them: from the point of the line nearest the centre).
std::vector<Job> torusJobs(int n) {
    Rng g(11);
    const Torus torus = reportTorus();
    std::vector<Job> out;
    while (int(out.size()) < n) {
        const Vec3 o = 4.0 * glm::normalize(randomIn(g, 1.0));
        const Vec3 u = glm::normalize(randomIn(g, 1.0) - o);
        const Vec3 b = o - glm::dot(o, u) * u;
        Job j{torus.quarticAlong(b, u), -1.5, 1.5, {}};
        j.lineBase = b, j.lineDir = u;
        out.push_back(std::move(j));
    }
    return out;
}

// The torus jobs for the tube row: the same lines, with the 50-digit roots of the line's exact
// quartic as the reference (the tube form is solved from the line, not from p's rounded
// coefficients, so that rounding is part of its error).
std::vector<Job> torusLineJobs(const std::vector<Job>& torus) {
    const Torus shape = reportTorus();
    std::vector<Job> out = torus;
    for (Job& j : out) {
        j.reference.clear();
        j.exact = rootref::realRoots(
            rootref::torusQuartic(shape.majorRadius, shape.minorRadius, j.lineBase, j.lineDir),
            Big(j.lo), Big(j.hi));
        for (const Big& r : j.exact) j.reference.push_back(r.convert_to<double>());
        j.resolvable = true;
    }
    return out;
}

// Rays from 4 units away through the surface s (the product of degree / 2 origin-centred
// spheres, radii^2 0.25 .. 1.4, aimed within 1.5; or the close shells, aimed within 0.99): the
// chord polynomial AlgebraicSurface hands its solver, and the line itself (for the spans rows).
std::vector<Job> shellJobs(const AlgebraicSurface& s, uint64_t seed, int n, double aim) {
    Rng g(seed);
    std::vector<Job> out;
    while (int(out.size()) < n) {
        const Vec3 o = 4.0 * glm::normalize(randomIn(g, 1.0));
        const Vec3 d = randomIn(g, aim) - o;
        AlgebraicSurface::Chord c;
        if (!s.chord(o, d, c)) continue;
        Job j{c.poly, c.uLo, c.uHi, {}};
        j.lineBase = o, j.lineDir = d;
        out.push_back(std::move(j));
    }
    return out;
}

// The issue-23 shells 5e-7 apart, (x^2+y^2+z^2-1)(x^2+y^2+z^2-1.000001), in the box [-2, 2]^3.
AlgebraicSurface closeShellSurface() {
    const ExactPolynomial x = ExactPolynomial::x(), y = ExactPolynomial::y(),
                          z = ExactPolynomial::z();
    const ExactPolynomial r2 = *x.times(x) + *y.times(y) + *z.times(z);
    return AlgebraicSurface::make(
        *(r2 - ExactPolynomial::constant(1.0)).times(r2 - ExactPolynomial::constant(1.000001)),
        {Vec3(-2.0), Vec3(2.0)});
}

// The shell jobs for the spans rows: the same lines, with the 50-digit roots in t of G(o - centre
// + t d) on the surface's own double coefficients (rootref::trivariateLine) inside the chord.
std::vector<Job> surfaceLineJobs(const AlgebraicSurface& s, const std::vector<Job>& chords) {
    std::vector<Job> out = chords;
    for (Job& j : out) {
        AlgebraicSurface::Chord c;
        s.chord(j.lineBase, j.lineDir, c);
        j.exact = rootref::realRoots(
            rootref::trivariateLine(s.data->g, s.data->centre, j.lineBase, j.lineDir), Big(c.tIn),
            Big(c.tOut));
        j.reference.clear();
        for (const Big& r : j.exact) j.reference.push_back(r.convert_to<double>());
        j.resolvable = true;
    }
    return out;
}

// A polynomial with the given real roots times (t^2 + 1)^pairs, coefficients rounded once.
Polynomial fromRoots(const std::vector<double>& roots, int complexPairs) {
    std::vector<Big> c = {Big(1)};
    auto times = [&c](std::vector<Big> factor) {
        std::vector<Big> out(c.size() + factor.size() - 1, Big(0));
        for (size_t i = 0; i < c.size(); ++i)
            for (size_t k = 0; k < factor.size(); ++k) out[i + k] += c[i] * factor[k];
        c = out;
    };
    for (double r : roots) times({Big(-r), Big(1)});
    for (int i = 0; i < complexPairs; ++i) times({Big(1), Big(0), Big(1)});
    Polynomial p = Polynomial::ofDegree(int(c.size()) - 1);
    for (size_t i = 0; i < c.size(); ++i) p[int(i)] = c[i].convert_to<double>();
    return p;
}

// n jobs on [lo, hi]: each a polynomial with the real roots that drawRoots(g, roots) appends
// (false: rejected, drawn again) times (t^2 + 1)^pairs, from one generator seeded with seed.
template <class DrawRoots>
std::vector<Job> jobsFromRoots(int n, uint64_t seed, double lo, double hi, int pairs,
                               DrawRoots drawRoots) {
    Rng g(seed);
    std::vector<Job> out;
    while (int(out.size()) < n) {
        std::vector<double> roots;
        if (drawRoots(g, roots)) out.push_back({fromRoots(roots, pairs), lo, hi, {}});
    }
    return out;
}

// Separated real roots in [-4, 4] (at least 0.05 apart); with `pairs` complex pairs on top.
std::vector<Job> separatedJobs(int degree, int n, uint64_t seed) {
    std::uniform_real_distribution<double> u(-4.0, 4.0);
    const int pairs = degree >= 4 ? 1 : 0;
    return jobsFromRoots(n, seed, -5.0, 5.0, pairs, [&](Rng& g, std::vector<double>& roots) {
        while (int(roots.size()) < degree - 2 * pairs) {
            const double r = u(g);
            bool ok = true;
            for (double s : roots) ok = ok && std::abs(s - r) >= 0.05;
            if (ok) roots.push_back(r);
        }
        return true;
    });
}

// Flocke's cluster: four roots 2 + k / 1000 (k distinct in 0..7), shifted at random.
std::vector<Job> clusterJobs(int n) {
    std::uniform_real_distribution<double> shift(-1.0, 1.0);
    return jobsFromRoots(n, 23, -5.0, 5.0, 0, [&](Rng& g, std::vector<double>& roots) {
        std::vector<int> ks = {0, 1, 2, 3, 4, 5, 6, 7};
        std::shuffle(ks.begin(), ks.end(), g);
        const double s = shift(g);
        for (int i = 0; i < 4; ++i) roots.push_back(2.0 + s + ks[size_t(i)] / 1000.0);
        return true;
    });
}

// A pair of roots 1e-5 apart (a nearly tangent ray) among two separated ones, degree 4.
std::vector<Job> nearDoubleJobs(int n) {
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    return jobsFromRoots(n, 29, -5.0, 5.0, 0, [&](Rng& g, std::vector<double>& roots) {
        const double a = u(g), b = u(g), c = u(g);
        if (std::abs(a - b) < 0.1 || std::abs(a - c) < 0.1 || std::abs(b - c) < 0.1) return false;
        roots = {a, a + 1e-5, b, c};
        return true;
    });
}

// Four roots over seven decades (1e-3 .. 1e4, random signs).
std::vector<Job> wideRangeJobs(int n) {
    std::uniform_real_distribution<double> decade(-3.0, 4.0);
    return jobsFromRoots(n, 31, -2e4, 2e4, 0, [&](Rng& g, std::vector<double>& roots) {
        for (int i = 0; i < 4; ++i)
            roots.push_back((g() & 1 ? 1.0 : -1.0) * std::pow(10.0, decade(g)));
        std::sort(roots.begin(), roots.end());
        bool ok = true;
        for (size_t i = 1; i < roots.size(); ++i)
            ok = ok && roots[i] - roots[i - 1] > 1e-3 * std::abs(roots[i]);
        return ok;
    });
}

// ---- Measuring ----

// Errors and counts of solveOne(job, roots) -> count over the jobs, then its rate: whole passes
// over the jobs until minSeconds have passed (at least 2); only solveOne runs inside the clock.
template <class SolveOne>
AccuracyRow measure(AccuracyRow row, const std::vector<Job>& jobs, double minSeconds,
                    SolveOne solveOne) {
    row.rays = long(jobs.size());
    double roots[Polynomial::kMaxDegree];
    std::vector<double> errors, ulps;
    long nearest = 0;
    for (const Job& j : jobs) {
        const int n = solveOne(j, roots);
        if (n != int(j.reference.size())) {
            ++row.wrongCounts;
            row.wrongResolvable += j.resolvable ? 1 : 0;
            continue;
        }
        double e = 0;
        for (int i = 0; i < n; ++i) {
            const double ref = j.reference[size_t(i)];
            e = std::max(e, std::abs(roots[i] - ref) / std::max(1.0, std::abs(ref)));
            // In ulps of t, against the 50-digit root itself.
            const Big exact = j.exact.empty() ? Big(ref) : j.exact[size_t(i)];
            ulps.push_back((abs(Big(roots[i]) - exact) / Big(ulpOf(ref))).convert_to<double>());
            nearest += roots[i] == ref ? 1 : 0;
        }
        errors.push_back(e);
    }
    const auto quantiles = [](std::vector<double>& v, double& max, double& p99, double& median) {
        std::sort(v.begin(), v.end());
        if (v.empty()) return;
        max = v.back();
        p99 = v[size_t(0.99 * double(v.size() - 1))];
        median = v[v.size() / 2];
    };
    quantiles(errors, row.maxError, row.p99Error, row.medianError);
    quantiles(ulps, row.maxUlps, row.p99Ulps, row.medianUlps);
    row.nearestShare = ulps.empty() ? 0.0 : double(nearest) / double(ulps.size());
    using Clock = std::chrono::steady_clock;
    long passes = 0;
    double sink = 0;
    const auto start = Clock::now();
    double seconds = 0;
    do {
        for (const Job& j : jobs) {
            const int n = solveOne(j, roots);
            sink += n > 0 ? roots[0] : 0.0;
        }
        ++passes;
        seconds = std::chrono::duration<double>(Clock::now() - start).count();
    } while (seconds < minSeconds || passes < 2);
    if (sink == 1.2345) std::fputs("", stderr);  // keeps the solves observable
    row.raysPerSecond = double(passes) * double(jobs.size()) / seconds;
    return row;
}

AccuracyRow measureSolver(const std::string& name, int degree, const std::vector<Job>& jobs,
                          Solver solver, double relTol, Polisher polisher, double minSeconds) {
    AccuracyRow row{name, degree, solverName(solver), "double", relTol};
    row.polisher = polisherName(polisher);
    return measure(row, jobs, minSeconds, [solver, relTol, polisher](const Job& j, double* roots) {
        return solve(j.p, j.lo, j.hi, roots, solver, relTol, polisher);
    });
}

// The exact path: the 50-digit reference itself (RootReference.h) as a solver, rounded to
// double: what a root to the last bit costs without double-double.
AccuracyRow measureReference(const std::string& name, int degree, const std::vector<Job>& jobs,
                             double minSeconds) {
    return measure({name, degree, "reference-50-digit", "cpp_bin_float_50", 0.0}, jobs, minSeconds,
                   [](const Job& j, double* roots) {
                       std::vector<Big> c(size_t(j.p.degree() + 1));
                       for (int i = 0; i <= j.p.degree(); ++i) c[size_t(i)] = j.p[i];
                       int n = 0;
                       for (const Big& r : rootref::realRoots(c, Big(j.lo), Big(j.hi)))
                           roots[n++] = r.convert_to<double>();
                       return n;
                   });
}

// AlgebraicSurface::spans with Solver::Auto and the polisher on each job's line (row solver
// "spans"): its surface crossings (span ends on face 6) against the exact roots of the line.
AccuracyRow measureSurfaceSpans(const std::string& name, int degree, AlgebraicSurface surface,
                                const std::vector<Job>& lineJobs, Polisher polisher,
                                double minSeconds) {
    surface.polisher = polisher;
    AccuracyRow row{name, degree, "spans", "double", 0.0};
    row.polisher = polisherName(polisher);
    return measure(row, lineJobs, minSeconds, [surface](const Job& j, double* roots) {
        LocalSpans s;
        surface.spans(j.lineBase, j.lineDir, s);
        int n = 0;
        for (int i = 0; i < s.count; ++i) {
            if (s.entries[i].faceIn == AlgebraicSurface::kSurfaceFace)
                roots[n++] = s.entries[i].tIn;
            if (s.entries[i].faceOut == AlgebraicSurface::kSurfaceFace)
                roots[n++] = s.entries[i].tOut;
        }
        return n;
    });
}

// Torus::spans on each job's line, bounding tests included: the span ends are the roots. With
// Solver::Auto, the tube form's monotone pieces (row "tube"); with Solver::ClosedForm, the
// quartic's roots polished on the tube form (row "quartic-spans"), for comparison on the same
// reference.
AccuracyRow measureTorusSpans(const std::vector<Job>& lineJobs, Solver solver, Polisher polisher,
                              double minSeconds) {
    Torus torus = reportTorus();
    torus.solver = solver;
    torus.polisher = polisher;
    const char* name = solver == Solver::Auto ? "tube" : "quartic-spans";
    AccuracyRow row{"torus", 4, name, "double", 0.0};
    row.polisher = polisherName(polisher);
    return measure(row, lineJobs, minSeconds, [torus](const Job& j, double* roots) {
        LocalSpans s;
        torus.spans(j.lineBase, j.lineDir, s);
        int n = 0;
        for (int i = 0; i < s.count; ++i)
            roots[n++] = s.entries[i].tIn, roots[n++] = s.entries[i].tOut;
        return n;
    });
}

// The same Yuksel code (ScalarYuksel.h) on p's coefficients rounded to T, range and roots in
// T: what the scalar type alone costs and buys.
template <class T>
AccuracyRow measureScalar(const std::string& name, int degree, const std::vector<Job>& jobs,
                          double minSeconds) {
    const char* type = std::is_same_v<T, float> ? "float" : "double";
    return measure({name, degree, std::string("yuksel<") + type + ">", type, 0.0}, jobs, minSeconds,
                   [](const Job& j, double* roots) {
                       const T* c;
                       if constexpr (std::is_same_v<T, float>)
                           c = j.pf.data();
                       else
                           c = j.pd.data();
                       T r[Polynomial::kMaxDegree];
                       const int n = yukselRootsT<T>(c, j.p.degree(), T(j.lo), T(j.hi), r);
                       for (int i = 0; i < n; ++i) roots[i] = double(r[i]);
                       return n;
                   });
}

// v through one printf format (a single double conversion, e.g. "%.2e").
std::string formatted(const char* format, double v) {
    char b[32];
    std::snprintf(b, sizeof b, format, v);
    return b;
}
std::string sci(double v) {
    return formatted("%.2e", v);
}
std::string ratio(double v) {
    return formatted("%.2f", v);
}
std::string fixed0(double v) {
    return formatted("%.0f", v);
}

std::string csvText(const std::vector<AccuracyRow>& rows) {
    std::ostringstream csv;
    csv << "class,degree,solver,polisher,scalar,rel_tol,rays_per_second,max_error,p99_error,"
           "median_error,max_ulps,p99_ulps,median_ulps,nearest_share,wrong_counts,"
           "wrong_resolvable,rays\n";
    for (const AccuracyRow& r : rows)
        csv << r.surfaceClass << ',' << r.degree << ',' << r.solver << ',' << r.polisher << ','
            << r.scalar << ',' << r.relTol << ',' << r.raysPerSecond << ',' << r.maxError << ','
            << r.p99Error << ',' << r.medianError << ',' << r.maxUlps << ',' << r.p99Ulps << ','
            << r.medianUlps << ',' << r.nearestShare << ',' << r.wrongCounts << ','
            << r.wrongResolvable << ',' << r.rays << '\n';
    return csv.str();
}

std::string markdownText(const std::vector<AccuracyRow>& rows, int rays) {
    std::ostringstream md;
    md << "# Root solver accuracy vs time\n\n"
       << rays << " rays per class (half that per degree in the sweep); error = |root - "
       << "reference| / max(1, |reference|) against the 50-digit roots of the same double "
       << "polynomial; rel_tol 0 = roots to double precision. The torus's `tube` row is what "
       << "csgray runs on a torus (Torus::spans, Solver::Auto: the tube form on its monotone "
       << "pieces, bounding tests included) and `quartic-spans` the same call with the "
       << "closed-form quartic (its roots polished on the tube form); both are measured against "
       << "the 50-digit roots of the exact quartic of the same double line, not of a rounded "
       << "polynomial: the error is against the line itself (for `quartic-spans` it includes "
       << "the rounding of the quartic's coefficients). "
       << "The `spans` rows are AlgebraicSurface::spans (Solver::Auto) on the same lines, "
       << "measured against the 50-digit roots of G(o - centre + t d) from the surface's own "
       << "double coefficients; the polisher column is the refinement after isolation "
       << "(primitives/solvers/Polish.h: none, auto = Newton in double-double where a condition "
       << "estimate asks, newton, laguerre, bairstow). `reference-50-digit` is the exact path "
       << "(the reference itself, timed). "
       << "Written by `csgray bench accuracy` (viewer/cli/accuracy/AccuracyReport.cpp); "
       << "plots: accuracy_pareto.svg, ulps_pareto.svg, degree_sweep.svg.\n\n";
    // Float against double first: the same solver code (ScalarYuksel.h), two scalar types.
    md << "## float vs double (the same Yuksel code, roots to full precision of the type)\n\n"
       << "| class | degree | float rays/s | double rays/s | float/double time | float max "
          "error | double max error | float p99 | double p99 | float wrong | double wrong "
          "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (size_t i = 0; i + 1 < rows.size(); ++i) {
        const AccuracyRow& f = rows[i];
        const AccuracyRow& d = rows[i + 1];
        if (f.solver != "yuksel<float>" || d.solver != "yuksel<double>") continue;
        md << "| " << f.surfaceClass << " | " << f.degree << " | " << fixed0(f.raysPerSecond)
           << " | " << fixed0(d.raysPerSecond) << " | " << ratio(d.raysPerSecond / f.raysPerSecond)
           << " | " << sci(f.maxError) << " | " << sci(d.maxError) << " | " << sci(f.p99Error)
           << " | " << sci(d.p99Error) << " | " << f.wrongCounts << " / " << f.rays << " | "
           << d.wrongCounts << " / " << d.rays << " |\n";
    }
    // Errors in ulps of t at full precision, by solver and polisher.
    md << "\n## Errors in ulps of t (full precision; exact = the 50-digit root, the double "
          "nearest it is within 0.5 ulp)\n\n| class | degree | solver | polisher | rays/s | max "
          "ulps | p99 ulps | median ulps | nearest | wrong counts |\n"
          "|---|---:|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const AccuracyRow& r : rows) {
        if (r.relTol != 0.0 || r.scalar == "float") continue;
        md << "| " << r.surfaceClass << " | " << r.degree << " | " << r.solver << " | "
           << r.polisher << " | " << fixed0(r.raysPerSecond) << " | "
           << formatted("%.3g", r.maxUlps) << " | " << formatted("%.3g", r.p99Ulps) << " | "
           << formatted("%.3g", r.medianUlps) << " | "
           << formatted("%.1f %%", 100.0 * r.nearestShare) << " | " << r.wrongCounts << " / "
           << r.rays << " |\n";
    }
    md << "\n## Every row\n\n| class | degree | solver | polisher | rel_tol | rays/s | max error "
          "| p99 error | max ulps | wrong counts | of them resolvable |\n"
          "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const AccuracyRow& r : rows)
        md << "| " << r.surfaceClass << " | " << r.degree << " | " << r.solver << " | "
           << r.polisher << " | " << (r.relTol == 0 ? std::string("0") : sci(r.relTol)) << " | "
           << fixed0(r.raysPerSecond) << " | " << sci(r.maxError) << " | " << sci(r.p99Error)
           << " | " << formatted("%.3g", r.maxUlps) << " | " << r.wrongCounts << " / " << r.rays
           << " | " << r.wrongResolvable << " |\n";
    return md.str();
}

}  // namespace

bool writeAccuracyReport(const AccuracyReportOptions& options, std::string* error) {
    const std::filesystem::path& dir = options.dir;
    const int rays = std::max(10, options.rays);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        *error = "cannot create directory " + dir.string() + (ec ? ": " + ec.message() : "");
        return false;
    }

    struct Class {
        std::string name;
        int degree;
        std::vector<Job> jobs;
        bool sweepTolerance;  // false: the degree sweep, at full accuracy only
        const AlgebraicSurface* surface = nullptr;  // a surface class: its spans rows too
    };
    std::vector<Class> classes;
    const AlgebraicSurface shells[] = {shellSurface(4), shellSurface(8), shellSurface(16)};
    const AlgebraicSurface closeShells = closeShellSurface();
    classes.push_back({"torus", 4, torusJobs(rays), true});
    for (int k = 0; k < 3; ++k) {
        const int d = 4 << k;
        classes.push_back({"shells", d, shellJobs(shells[k], 17 + uint64_t(d), rays, 1.5), true,
                           d <= 8 ? &shells[k] : nullptr});  // degree 16: the 50-digit line is slow
    }
    classes.push_back(
        {"close-shells", 4, shellJobs(closeShells, 2301, rays, 0.99), true, &closeShells});
    classes.push_back({"cluster", 4, clusterJobs(rays), true});
    classes.push_back({"near-double", 4, nearDoubleJobs(rays), true});
    classes.push_back({"wide-range", 4, wideRangeJobs(rays), true});
    for (int d = 2; d <= 20; ++d)
        classes.push_back(
            {"degree-sweep", d, separatedJobs(d, std::max(5, rays / 2), 41 + uint64_t(d)), false});
    for (Class& c : classes) {
        long unresolvable = 0;
        for (Job& j : c.jobs) {
            addReference(j);
            unresolvable += j.resolvable ? 0 : 1;
        }
        if (options.progress)
            std::fprintf(stderr, "%s %d: %ld of %zu rays not resolvable in double\n",
                         c.name.c_str(), c.degree, unresolvable, c.jobs.size());
    }

    const double tolerances[] = {1e-3, 1e-6, 1e-9, 1e-12, 1e-15, 0.0};
    std::vector<AccuracyRow> rows;
    auto report = [&](const AccuracyRow& r) {
        rows.push_back(r);
        if (!options.progress) return;
        std::fprintf(stderr,
                     "%-12s %2d %-16s %-8s tol %-7g %10.0f rays/s max %s p99 %s ulps max %.3g "
                     "p99 %.3g wrong %ld (%ld resolvable)\n",
                     r.surfaceClass.c_str(), r.degree, r.solver.c_str(), r.polisher.c_str(),
                     r.relTol, r.raysPerSecond, sci(r.maxError).c_str(), sci(r.p99Error).c_str(),
                     r.maxUlps, r.p99Ulps, r.wrongCounts, r.wrongResolvable);
    };
    const double minSeconds = options.minSeconds;
    for (const Class& c : classes) {
        for (Solver solver : kAllSolvers) {
            // Closed forms exist up to degree 4 only (above, ClosedForm is Yuksel).
            if (solver == Solver::ClosedForm && c.degree > 4) continue;
            for (double tol : tolerances) {
                if (!c.sweepTolerance && tol != 0.0) continue;
                // The closed forms ignore the tolerance: one row is the whole story.
                if (solver == Solver::ClosedForm && tol != 0.0) continue;
                // No polish at a tolerance (solve() skips it); at full precision the isolating
                // solver alone, then with the Auto polish.
                report(measureSolver(c.name, c.degree, c.jobs, solver, tol, Polisher::None,
                                     minSeconds));
                if (tol == 0.0)
                    report(measureSolver(c.name, c.degree, c.jobs, solver, tol, Polisher::Auto,
                                         minSeconds));
            }
        }
        // Every polisher after Solver::Auto's isolation.
        for (Polisher polisher : {Polisher::Newton, Polisher::Laguerre, Polisher::Bairstow})
            report(
                measureSolver(c.name, c.degree, c.jobs, Solver::Auto, 0.0, polisher, minSeconds));
        // The exact path, where it is cheap enough to time (degree 4).
        if (c.degree == 4 && c.sweepTolerance)
            report(measureReference(c.name, c.degree, c.jobs, minSeconds));
        if (c.name == "torus") {
            const std::vector<Job> lineJobs = torusLineJobs(c.jobs);
            for (Solver solver : {Solver::Auto, Solver::ClosedForm})
                for (Polisher polisher : kAllPolishers)
                    report(measureTorusSpans(lineJobs, solver, polisher, minSeconds));
        }
        if (c.surface) {
            const std::vector<Job> lineJobs = surfaceLineJobs(*c.surface, c.jobs);
            for (Polisher polisher : kAllPolishers)
                report(measureSurfaceSpans(c.name, c.degree, *c.surface, lineJobs, polisher,
                                           minSeconds));
        }
        report(measureScalar<float>(c.name, c.degree, c.jobs, minSeconds));
        report(measureScalar<double>(c.name, c.degree, c.jobs, minSeconds));
    }

    const std::pair<const char*, std::string> files[] = {
        {"accuracy.csv", csvText(rows)},
        {"accuracy.md", markdownText(rows, rays)},
        {"accuracy_pareto.svg", paretoSvg(rows)},
        {"ulps_pareto.svg", paretoSvg(rows, true)},
        {"degree_sweep.svg", degreeSweepSvg(rows)}};
    for (const auto& [name, text] : files) {
        *error = csg::writeFileAtomically(dir / name, text);
        if (!error->empty()) return false;
    }
    if (options.progress)
        std::fprintf(stderr,
                     "wrote accuracy.csv, accuracy.md, accuracy_pareto.svg, ulps_pareto.svg "
                     "and degree_sweep.svg in %s\n",
                     dir.c_str());
    return true;
}

}  // namespace csg
