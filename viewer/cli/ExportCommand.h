// `csgray export`: a part to a mesh file (GLB, glTF or OBJ) made from its own ray casts.
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "export". Returns the process exit code.
int exportCommand(std::span<const std::string> args);

}  // namespace viewer
