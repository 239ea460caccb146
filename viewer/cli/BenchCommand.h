// `csgray bench accuracy -o DIR`: the root solvers' accuracy-versus-time report
// (viewer/cli/accuracy/AccuracyReport.h) written into DIR.
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "bench". Returns the process exit code.
int benchCommand(std::span<const std::string> args);

}  // namespace viewer
