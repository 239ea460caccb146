// Where simplification (csg/mesh/Simplify.h) spends its time on a big grid mesh: the grid's mesh
// of a part (tessellate() without simplification, as `csgray export --no-simplify` makes it) is
// simplified with the budget tessellate() would give it, and the phases (building the mesh
// structure, decimating, extracting the result) are timed. A plain program: one run, figures.
//
//   simplify_bench PART.scad [--tolerance T] [--threads N] [--budget B] [--runs N]
//                  [--save FILE | --load FILE] [--out FILE] [--checked | --unchecked]
//                  [--count-crossings]
//
// --save writes the grid's mesh (and the budget) to FILE in a raw binary form and --load reads
// it back, so repeated runs skip meshing (GLB and OBJ would round the positions; this keeps
// them bit for bit); --out writes the simplified mesh of the last run in the same form (to check
// that a change to simplify() keeps its result: compare the files). --budget overrides the budget;
// --threads is simplify()'s worker count (0: all cores). --unchecked simplifies without refusing
// collapses that make triangles cross (what the check costs and what it prevents), --checked with
// it (simplify()'s default); --count-crossings counts the result's self-intersections
// (findSelfIntersections, as `csgray compare` does). Prints wall and CPU seconds of each run:
// read CPU time on a shared machine.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/Simplify.h"
#include "csg/mesh/Tessellate.h"
#include "io/Diagnostic.h"
#include "io/Evaluate.h"

namespace {

int usage() {
    std::fputs(
        "usage: simplify_bench PART.scad [--tolerance T] [--threads N] [--budget B] [--runs N] "
        "[--save FILE | --load FILE] [--out FILE] [--checked | --unchecked] [--count-crossings]\n",
        stderr);
    return 2;
}

double cpuSeconds() {
    return double(std::clock()) / CLOCKS_PER_SEC;
}

template <class T>
void writeVector(std::ofstream& out, const std::vector<T>& v) {
    const uint64_t n = v.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof n);
    out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(n * sizeof(T)));
}

bool writeMeshFile(const std::string& file, double budget, const csg::TriangleMesh& mesh) {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(&budget), sizeof budget);
    writeVector(out, mesh.positions);
    writeVector(out, mesh.normals);
    writeVector(out, mesh.triangles);
    writeVector(out, mesh.triangleMaterial);
    return bool(out);
}

template <class T>
bool readVector(std::ifstream& in, std::vector<T>& v) {
    uint64_t n = 0;
    if (!in.read(reinterpret_cast<char*>(&n), sizeof n) || n > (uint64_t(1) << 32)) return false;
    v.resize(n);
    return bool(in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T))));
}

}  // namespace

int main(int argc, char** argv) {
    std::string part, save, load, outFile;
    double tolerance = 0.0, budget = 0.0;
    int threads = 0, runs = 1;
    bool refuseCrossings = true, countCrossings = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.empty() || arg[0] != '-') {
            part = arg;
            continue;
        }
        if (arg == "--unchecked" || arg == "--checked") {
            refuseCrossings = arg == "--checked";
            continue;
        }
        if (arg == "--count-crossings") {
            countCrossings = true;
            continue;
        }
        if (i + 1 >= argc) return usage();
        const char* value = argv[++i];
        if (arg == "--tolerance")
            tolerance = std::atof(value);
        else if (arg == "--threads")
            threads = std::atoi(value);
        else if (arg == "--budget")
            budget = std::atof(value);
        else if (arg == "--runs")
            runs = std::max(1, std::atoi(value));
        else if (arg == "--save")
            save = value;
        else if (arg == "--load")
            load = value;
        else if (arg == "--out")
            outFile = value;
        else
            return usage();
    }

    csg::TriangleMesh grid;
    double gridBudget = 0.0;
    if (!load.empty()) {
        std::ifstream in(load, std::ios::binary);
        if (!in.read(reinterpret_cast<char*>(&gridBudget), sizeof gridBudget) ||
            !readVector(in, grid.positions) || !readVector(in, grid.normals) ||
            !readVector(in, grid.triangles) || !readVector(in, grid.triangleMaterial)) {
            std::fprintf(stderr, "simplify_bench: cannot read %s\n", load.c_str());
            return 1;
        }
    } else {
        if (part.empty()) return usage();
        const io::EvaluateResult loaded = io::evaluateFile(part);
        if (!loaded.model) {
            for (const auto& diagnostic : loaded.diagnostics)
                std::fprintf(stderr, "%s\n", io::formatDiagnostic(diagnostic).c_str());
            std::fprintf(stderr, "simplify_bench: %s does not evaluate\n", part.c_str());
            return 1;
        }
        const csg::Scene scene = csg::Scene::compile(loaded.model->root);
        csg::TessellateOptions options;
        options.tolerance = tolerance;
        options.simplify = false;
        const auto start = std::chrono::steady_clock::now();
        const csg::TessellateResult r = csg::tessellate(scene, options);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        grid = r.mesh;
        gridBudget = csg::firstSimplifyBudget(r);  // the budget of tessellate()'s first try
        std::printf("grid mesh: %zu triangles, T %.6g, measured %.6g / %.6g, %d passes, %.2f s\n",
                    grid.triangles.size(), r.tolerance, r.error.max, r.backError.max, r.passes,
                    seconds);
        if (!save.empty()) {
            if (!writeMeshFile(save, gridBudget, grid)) {
                std::fprintf(stderr, "simplify_bench: cannot write %s\n", save.c_str());
                return 1;
            }
        }
    }
    if (budget <= 0.0) budget = gridBudget;
    std::printf("simplify: %zu triangles, %zu vertices, budget %.6g, threads %d\n",
                grid.triangles.size(), grid.positions.size(), budget, threads);
    for (int run = 0; run < runs; ++run) {
        csg::SimplifyStats stats;
        const double cpu0 = cpuSeconds();
        const auto start = std::chrono::steady_clock::now();
        const csg::TriangleMesh coarse =
            csg::simplify(grid, budget, &stats, threads, refuseCrossings);
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double cpu = cpuSeconds() - cpu0;
        const bool manifold = csg::checkTopology(coarse).closedManifold();
        if (stats.blocks > 0)
            std::printf("run %d: %d blocks: %.3f s, %llu triangles left for the whole pass\n", run,
                        stats.blocks, stats.blocksSeconds,
                        (unsigned long long)stats.trianglesAfterBlocks);
        std::printf(
            "run %d: %llu -> %llu triangles, wall %.3f s (build %.3f, decimate %.3f, extract "
            "%.3f), cpu %.3f s, %s\n",
            run, (unsigned long long)stats.trianglesBefore,
            (unsigned long long)stats.trianglesAfter, wall, stats.buildSeconds,
            stats.decimateSeconds, stats.extractSeconds, cpu,
            manifold ? "closed manifold" : "NOT A CLOSED MANIFOLD");
        std::printf("run %d: %llu collapses, %llu refused for crossing\n", run,
                    (unsigned long long)stats.collapses, (unsigned long long)stats.refusedCrossing);
        if (countCrossings) {
            const csg::SelfIntersections x = csg::findSelfIntersections(coarse);
            std::printf("run %d: self-intersections %llu, %llu of them coplanar\n", run,
                        (unsigned long long)x.pairs, (unsigned long long)x.coplanarPairs);
        }
        if (run + 1 == runs && !outFile.empty() && !writeMeshFile(outFile, budget, coarse)) {
            std::fprintf(stderr, "simplify_bench: cannot write %s\n", outFile.c_str());
            return 1;
        }
    }
    return 0;
}
