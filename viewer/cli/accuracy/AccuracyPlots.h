// The accuracy report's plots as SVG text, drawn by our own code so that `csgray bench
// accuracy` needs nothing beyond the build (any browser shows them).
#pragma once

#include <string>
#include <vector>

#include "viewer/cli/accuracy/AccuracyReport.h"

namespace csg {

// One panel per surface class (the degree sweep excluded): ns per ray (solve only, log) against
// the 99th-percentile error (log; 0 drawn at 1e-17), one line per solver through its tolerance
// settings from coarse to full, a cross where a setting has wrong root counts, and the Pareto
// front (nothing both faster and more accurate among the settings without wrong counts) in black.
// With ulps, the y axis is the max error in ulps of t (AccuracyRow::maxUlps; 0 drawn at 0.01)
// and a series is a solver with its polisher.
std::string paretoSvg(const std::vector<AccuracyRow>& rows, bool ulps = false);

// The degree sweep: rays per second and max error against degree 2..20, one line per solver.
std::string degreeSweepSvg(const std::vector<AccuracyRow>& rows);

}  // namespace csg
