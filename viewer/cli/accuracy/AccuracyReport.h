// The accuracy-versus-time report of the root solvers (issue 5), as a library so that the
// command line (`csgray bench accuracy -o DIR`) runs it: one implementation.
//
// For every solver, surface class and tolerance: rays per second of solve() alone against the
// error distribution (max, 99th percentile, median) and the wrong root counts, measured
// against the 50-digit roots of the same double polynomial, also in ulps of t, with each
// polisher after isolation (Polish.h); the surfaces' and the torus's span ends against the
// exact roots of their line's polynomial; a degree sweep 2..20; and float against double for
// the same solver code (ScalarYuksel.h). Writes DIR/accuracy.csv, DIR/accuracy.md,
// DIR/accuracy_pareto.svg, DIR/ulps_pareto.svg and DIR/degree_sweep.svg.
#pragma once

#include <filesystem>
#include <string>

namespace csg {

// One measured setting: a solver on the rays of one surface class at one tolerance.
struct AccuracyRow {
    std::string surfaceClass;
    int degree = 0;
    std::string solver;   // solverName(), or "yuksel<float>" / "yuksel<double>" (ScalarYuksel.h)
    std::string scalar;   // "double", or "float" for the float path
    double relTol = 0.0;  // 0: roots to full precision
    double raysPerSecond = 0.0;
    double maxError = 0.0, p99Error = 0.0, medianError = 0.0;  // |root - ref| / max(1, |ref|)
    // The polisher after isolation (Polish.h's name; "none": the isolating solver's roots).
    std::string polisher = "none";
    // Per root: |root - exact| / ulp(exact), exact the 50-digit root (the double nearest it is
    // within 0.5); and the share of roots that are that nearest double.
    double maxUlps = 0.0, p99Ulps = 0.0, medianUlps = 0.0, nearestShare = 0.0;
    long wrongCounts = 0;
    long wrongResolvable = 0;  // wrong counts on rays double precision can resolve
    long rays = 0;
};

struct AccuracyReportOptions {
    std::filesystem::path dir = "accuracy";  // created when missing
    int rays = 2000;                         // per surface class (half per degree of the sweep)
    double minSeconds = 0.05;                // timing per row: whole passes until this long
    bool progress = true;                    // one line per measured row on stderr
};

// Runs the report and writes its files. False (with *error set, nothing half-written left
// under the final names) when DIR cannot be created or a file cannot be written.
bool writeAccuracyReport(const AccuracyReportOptions& options, std::string* error);

}  // namespace csg
