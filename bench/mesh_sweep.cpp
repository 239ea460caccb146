// What mesh accuracy costs: `csgray export`'s meshing (csg::tessellate) of each part at a
// tolerance halved step by step, printing wall and CPU time, triangle counts (the grid's mesh and
// the simplified one written), the cell size reached, the grid planes added through thin walls
// and gaps (ThinFeatures.h) and the mesh-surface distances measured both ways. A plain program (no
// Google Benchmark): one run per tolerance, a table, not a timing of one call.
//
//   mesh_sweep PART.scad... [-o DIR] [--from T] [--steps N] [--max-cells N] [--threads N]
//              [--octree | --no-octree]
//
// --from defaults to 1/50 of each part's bounds diagonal; each step halves it. Writes
// DIR/mesh_sweep.csv, DIR/mesh_sweep.md and DIR/mesh_sweep.svg (time, triangles and distance
// against tolerance, log-log, one line per part; generated, not committed) (default DIR: the
// current directory); the table also goes to stdout. --octree merges flat blocks of cells
// (TessellateOptions::adaptive, off by default as in export), for before/after rows. CPU time (all
// threads) is the figure to read on a shared machine. The distances are tessellate's own
// measurements (MeshDistance.h: every vertex, centroid and edge midpoint of the mesh; 128^2 lines
// per axis from the surface).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "csg/mesh/Tessellate.h"
#include "io/Diagnostic.h"
#include "io/Evaluate.h"
#include "primitives/base/AtomicFile.h"

namespace {

int usage() {
    std::fputs(
        "usage: mesh_sweep PART.scad... [-o DIR] [--from T] [--steps N] [--max-cells N] "
        "[--threads N] [--octree | --no-octree]\n",
        stderr);
    return 2;
}

struct Point {
    double tolerance, seconds, cpu, gridTriangles, triangles, distance;
};

// Three log-log panels against tolerance (coarse on the left): CPU seconds, triangles (dashed:
// the grid's mesh), and the measured max distance both ways with the line distance = tolerance.
std::string sweepSvg(const std::vector<std::pair<std::string, std::vector<Point>>>& series) {
    const char* colors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                            "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
    constexpr double kW = 360, kH = 300, kPad = 50;
    std::ostringstream svg;
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << 3 * kW << "' height='" << kH + 20
        << "' font-family='sans-serif' font-size='11'>\n";
    auto range = [&](auto get, double& lo, double& hi) {
        lo = INFINITY;
        hi = -INFINITY;
        for (const auto& [name, pts] : series)
            for (const Point& p : pts)
                if (const double v = get(p); v > 0.0 && std::isfinite(v)) {
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
        if (!(lo < hi)) hi = lo * 10.0;
        lo = std::pow(10.0, std::floor(std::log10(lo)));
        hi = std::pow(10.0, std::ceil(std::log10(hi)));
    };
    double tlo, thi;
    range([](const Point& p) { return p.tolerance; }, tlo, thi);
    auto panel = [&](int index, const char* title, auto get, auto dashed, bool hasDashed,
                     bool diagonal) {
        double lo, hi;
        range(get, lo, hi);
        if (diagonal) {
            lo = std::min(lo, tlo);
            hi = std::max(hi, thi);
        }
        const double x0 = index * kW + kPad, x1 = (index + 1) * kW - 10, y0 = kH - 30, y1 = 25;
        auto X = [&](double t) { return x0 + (x1 - x0) * std::log(thi / t) / std::log(thi / tlo); };
        auto Y = [&](double v) { return y0 + (y1 - y0) * std::log(v / lo) / std::log(hi / lo); };
        svg << "<text x='" << x0 << "' y='15'>" << title << "</text>\n";
        svg << "<rect x='" << x0 << "' y='" << y1 << "' width='" << x1 - x0 << "' height='"
            << y0 - y1 << "' fill='none' stroke='black'/>\n";
        for (double d = lo; d <= hi * 1.001; d *= 10)
            svg << "<text x='" << x0 - 4 << "' y='" << Y(d) + 4 << "' text-anchor='end'>" << d
                << "</text>\n";
        for (double t = tlo; t <= thi * 1.001; t *= 10)
            svg << "<text x='" << X(t) << "' y='" << y0 + 14 << "' text-anchor='middle'>" << t
                << "</text>\n";
        svg << "<text x='" << (x0 + x1) / 2 << "' y='" << kH + 10
            << "' text-anchor='middle'>tolerance</text>\n";
        if (diagonal)
            svg << "<line x1='" << X(thi) << "' y1='" << Y(thi) << "' x2='" << X(tlo) << "' y2='"
                << Y(tlo) << "' stroke='black' stroke-dasharray='2,3'/>\n";
        int c = 0;
        for (const auto& [name, pts] : series) {
            for (int pass = 0; pass < (hasDashed ? 2 : 1); ++pass) {
                svg << "<polyline fill='none' stroke='" << colors[c % 10] << "'"
                    << (pass ? " stroke-dasharray='4,3'" : "") << " points='";
                for (const Point& p : pts) {
                    const double v = pass ? dashed(p) : get(p);
                    if (v > 0.0 && std::isfinite(v)) svg << X(p.tolerance) << ',' << Y(v) << ' ';
                }
                svg << "'/>\n";
            }
            if (index == 0)
                svg << "<text x='" << x0 + 6 << "' y='" << y1 + 14 + 13 * c << "' fill='"
                    << colors[c % 10] << "'>" << name << "</text>\n";
            ++c;
        }
    };
    auto none = [](const Point&) { return 0.0; };
    panel(
        0, "CPU seconds (all threads)", [](const Point& p) { return p.cpu; }, none, false, false);
    panel(
        1, "triangles (dashed: grid mesh before simplification)",
        [](const Point& p) { return p.triangles; }, [](const Point& p) { return p.gridTriangles; },
        true, false);
    panel(
        2, "measured max distance, both ways", [](const Point& p) { return p.distance; }, none,
        false, true);
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::filesystem::path> parts;
    std::filesystem::path dir = ".";
    double from = 0.0;
    int steps = 5, threads = 0;
    uint64_t maxCells = uint64_t(1) << 24;
    bool adaptive = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.empty() || arg[0] != '-') {
            parts.emplace_back(arg);
            continue;
        }
        if (arg == "--no-octree" || arg == "--octree") {
            adaptive = arg == "--octree";
            continue;
        }
        if (i + 1 >= argc) return usage();
        const char* value = argv[++i];
        if (arg == "-o")
            dir = value;
        else if (arg == "--from")
            from = std::atof(value);
        else if (arg == "--steps")
            steps = std::atoi(value);
        else if (arg == "--max-cells")
            maxCells = uint64_t(std::atof(value));
        else if (arg == "--threads")
            threads = std::atoi(value);
        else
            return usage();
    }
    if (steps < 1 || parts.empty()) return usage();
    std::string csv =
        "part,tolerance,seconds,cpu_seconds,grid_triangles,triangles,cell,cells,thin_planes,"
        "passes,mesh_to_surface,surface_to_mesh,met,capped,stalled\n";
    std::string md =
        "| part | tolerance | wall s | CPU s | grid triangles | triangles | cell | thin planes | "
        "passes | mesh→surface | surface→mesh | met |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<std::pair<std::string, std::vector<Point>>> series;
    for (const std::filesystem::path& part : parts) {
        // Step 1: the part.
        const io::EvaluateResult loaded = io::evaluateFile(part);
        if (!loaded.ok()) {
            for (const auto& diagnostic : loaded.diagnostics)
                std::fprintf(stderr, "%s\n", io::formatDiagnostic(diagnostic).c_str());
            std::fprintf(stderr, "mesh_sweep: %s does not evaluate\n", part.c_str());
            return 1;
        }
        const csg::Scene scene = csg::Scene::compile(loaded.model->root);
        const csg::Bounds3 box = scene.bounds();
        if (box.empty() || !box.finite()) {
            std::fprintf(stderr, "mesh_sweep: %s is empty or unbounded\n", part.c_str());
            return 1;
        }
        // Step 2: the sweep.
        const std::string name = part.filename().string();
        series.push_back({name, {}});
        char line[512];
        double tolerance = from > 0.0 ? from : glm::length(box.extent()) / 50.0;
        for (int step = 0; step < steps; ++step, tolerance *= 0.5) {
            csg::TessellateOptions options;
            options.tolerance = tolerance;
            options.maxCells = maxCells;
            options.threads = threads;
            options.adaptive = adaptive;
            const auto start = std::chrono::steady_clock::now();
            const std::clock_t cpuStart = std::clock();
            const csg::TessellateResult r = csg::tessellate(scene, options);
            const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            series.back().second.push_back({tolerance, seconds, cpu, double(r.gridTriangles),
                                            double(r.mesh.triangles.size()),
                                            std::max(r.error.max, r.backError.max)});
            std::snprintf(line, sizeof line,
                          "%s,%.6g,%.3f,%.3f,%llu,%zu,%.6g,%llu,%llu,%d,%.6g,%.6g,%d,%d,%d\n",
                          name.c_str(), tolerance, seconds, cpu,
                          (unsigned long long)r.gridTriangles, r.mesh.triangles.size(), r.cellSize,
                          (unsigned long long)r.cells, (unsigned long long)r.thinPlanes.added,
                          r.passes, r.error.max, r.backError.max, int(r.toleranceMet),
                          int(r.capped), int(r.stalled));
            csv += line;
            std::snprintf(
                line, sizeof line,
                "| %s | %.4g | %.2f | %.2f | %llu | %zu | %.4g | %llu | %d | %.3g | %.3g | %s |\n",
                name.c_str(), tolerance, seconds, cpu, (unsigned long long)r.gridTriangles,
                r.mesh.triangles.size(), r.cellSize, (unsigned long long)r.thinPlanes.added,
                r.passes, r.error.max, r.backError.max,
                r.toleranceMet
                    ? "yes"
                    : (r.capped ? "no (cell cap)" : (r.stalled ? "no (stalled)" : "no")));
            md += line;
            std::fputs(line, stdout);
            std::fflush(stdout);
        }
    }

    // Step 3: the files.
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const std::pair<const char*, std::string> files[] = {
        {"mesh_sweep.csv", csv}, {"mesh_sweep.md", md}, {"mesh_sweep.svg", sweepSvg(series)}};
    for (const auto& [file, text] : files) {
        if (const std::string error = csg::writeFileAtomically(dir / file, text); !error.empty()) {
            std::fprintf(stderr, "mesh_sweep: %s\n", error.c_str());
            return 3;
        }
    }
    return 0;
}
