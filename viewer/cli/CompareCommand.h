// `csgray compare`: how far a mesh (csgray's, OpenSCAD's, a CAD kernel's) is from a part's
// exact surface, both ways, plus volume, watertightness and orientation.
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "compare". Returns the process exit code.
int compareCommand(std::span<const std::string> args);

}  // namespace viewer
