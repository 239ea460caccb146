// Rays per second of every root solver on the polynomials that real rays produce: torus rays
// (the quartic of Torus::quarticAlong) and algebraic surfaces of degree 4 .. 16 (products of
// origin-centred spheres, AlgebraicSurface::chord). The rays and their polynomials are made
// once per benchmark (seeded), so only solve() is timed. items_per_second = rays per second.
//
//   solvers_bench --benchmark_filter='torus/'        every solver on torus rays
//   solvers_bench --benchmark_filter='shells/16/'    every solver at degree 16
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "primitives/AlgebraicSurface.h"
#include "primitives/Torus.h"
#include "primitives/solvers/reference/ShellSurface.h"

namespace {

using namespace csg;

struct Job {
    Polynomial p;
    double lo, hi;
};

Vec3 randomIn(std::mt19937_64& g, double r) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (;;) {
        const Vec3 v(u(g), u(g), u(g));
        if (glm::dot(v, v) <= 1.0) return r * v;
    }
}

// 4096 rays from 4 units away through the torus R = 1, r = 0.25 (about half hit).
const std::vector<Job>& torusJobs() {
    static const std::vector<Job> jobs = [] {
        std::mt19937_64 g(11);
        const Torus torus{1.0, 0.25};
        std::vector<Job> out;
        while (out.size() < 4096) {
            const Vec3 o = 4.0 * glm::normalize(randomIn(g, 1.0));
            const Vec3 u = glm::normalize(randomIn(g, 1.0) - o);
            const double tBase = -glm::dot(o, u);
            out.push_back({torus.quarticAlong(o + tBase * u, u), -1.5, 1.5});
        }
        return out;
    }();
    return jobs;
}

// 4096 rays through the product of degree / 2 spheres with radii 0.25 .. 1.4.
const std::vector<Job>& shellJobs(int degree) {
    static std::vector<Job> cache[Polynomial::kMaxDegree + 1];
    std::vector<Job>& jobs = cache[degree];
    if (!jobs.empty()) return jobs;
    const AlgebraicSurface s = shellSurface(degree);
    std::mt19937_64 g(17 + uint64_t(degree));
    while (jobs.size() < 4096) {
        const Vec3 o = 4.0 * glm::normalize(randomIn(g, 1.0));
        AlgebraicSurface::Chord c;
        if (s.chord(o, randomIn(g, 1.5) - o, c)) jobs.push_back({c.poly, c.uLo, c.uHi});
    }
    return jobs;
}

void run(benchmark::State& state, const std::vector<Job>& jobs, Solver solver, double relTol) {
    double roots[Polynomial::kMaxDegree];
    long found = 0;
    for (auto _ : state)
        for (const Job& j : jobs) {
            found += solve(j.p, j.lo, j.hi, roots, solver, relTol);
            benchmark::DoNotOptimize(roots);
        }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(jobs.size()));
    state.counters["roots/ray"] = double(found) / double(state.iterations() * jobs.size());
}

void registerAll() {
    for (Solver solver : kAllSolvers) {
        const std::string name = solverName(solver);
        benchmark::RegisterBenchmark(("torus/" + name).c_str(), [solver](benchmark::State& s) {
            run(s, torusJobs(), solver, 0.0);
        });
        for (int degree : {4, 6, 8, 12, 16}) {
            if (solver == Solver::ClosedForm && degree > 4) continue;
            benchmark::RegisterBenchmark(
                ("shells/" + std::to_string(degree) + "/" + name).c_str(),
                [solver, degree](benchmark::State& s) { run(s, shellJobs(degree), solver, 0.0); });
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    registerAll();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
