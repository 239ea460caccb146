// `csgray render`: a part to a PNG file (the preview renderer until issue 4's renderer lands).
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "render". Returns the process exit code.
int renderCommand(std::span<const std::string> args);

}  // namespace viewer
