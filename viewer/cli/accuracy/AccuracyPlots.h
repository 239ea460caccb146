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
std::string paretoSvg(const std::vector<AccuracyRow>& rows);

// The degree sweep: rays per second and max error against degree 2..16, one line per solver.
std::string degreeSweepSvg(const std::vector<AccuracyRow>& rows);

}  // namespace csg
