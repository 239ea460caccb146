// `csgray render`: a part to an image by the Whitted renderer (viewer/render/), or --preview.
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "render". Returns the process exit code.
int renderCommand(std::span<const std::string> args);

}  // namespace viewer
