// `csgray info`: what a part is made of, as JSON: node counts by kind, world bounds, the scene
// extras (camera, lights, background, materials) and the CSG tree after evaluation.
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "info". Returns the process exit code.
int infoCommand(std::span<const std::string> args);

}  // namespace viewer
