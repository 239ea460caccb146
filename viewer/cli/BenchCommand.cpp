#include "viewer/cli/BenchCommand.h"

#include <cstdio>
#include <string>

#include "viewer/cli/Cli.h"
#include "viewer/cli/accuracy/AccuracyReport.h"

namespace viewer {
namespace {

const char* const kHelp =
    "usage: csgray bench accuracy -o DIR [--rays N] [--min-time SECONDS] [--quiet]\n"
    "\n"
    "What each digit of accuracy costs: every root solver on every surface class (torus,\n"
    "shells of degree 4/8/16, decimal clusters, near-double roots, wide root ranges, and a\n"
    "degree sweep 2..16), at tolerances 1e-3 .. 1e-15 and full precision, against the\n"
    "50-digit roots of the same polynomials; and float vs double for the same solver code.\n"
    "Writes DIR/accuracy.csv, DIR/accuracy.md, DIR/accuracy_pareto.svg, DIR/degree_sweep.svg.\n"
    "\n"
    "options:\n"
    "  -o DIR               output directory (created when missing)\n"
    "  --rays N             rays per surface class, half that per degree of the sweep\n"
    "                       (default 2000: about two minutes on one core)\n"
    "  --min-time SECONDS   timing per row: whole passes over the rays until this long\n"
    "                       (default 0.05)\n"
    "  --quiet              no progress lines on stderr\n";

}  // namespace

int benchCommand(std::span<const std::string> args) {
    std::string report;
    csg::AccuracyReportOptions options;
    bool help = false, haveDir = false;
    ArgCursor cursor(args);
    while (!cursor.done()) {
        if (cursor.flag("--help") || cursor.flag("-h")) {
            help = true;
        } else if (auto dir = cursor.option("-o")) {
            options.dir = *dir;
            haveDir = true;
        } else if (auto rays = cursor.option("--rays")) {
            options.rays = parsePositiveInt(*rays, "--rays", 10000000);
        } else if (auto t = cursor.option("--min-time")) {
            options.minSeconds = parseNumberIn(*t, "--min-time", 0.0, 60.0);
        } else if (cursor.flag("--quiet")) {
            options.progress = false;
        } else if (report.empty() && !cursor.peek().starts_with("-")) {
            report = cursor.take();
            if (report != "accuracy") throw UsageError("unknown bench report '" + report + "'");
        } else {
            throw UsageError("unknown option '" + cursor.peek() + "'");
        }
    }
    if (help) {
        std::fputs(kHelp, stdout);
        return kExitOk;
    }
    if (report.empty()) throw UsageError("bench needs a report name: accuracy");
    if (!haveDir) throw UsageError("bench accuracy needs -o DIR");
    std::string error;
    if (!csg::writeAccuracyReport(options, &error)) {
        std::fprintf(stderr, "csgray: error: %s\n", error.c_str());
        return kExitIo;
    }
    return kExitOk;
}

}  // namespace viewer
