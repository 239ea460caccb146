// `csgray view PART`: an interactive window that ray-casts the part progressively, reloads it
// when its files change, and probes the ray under a click.
#pragma once

#include <span>
#include <string>

namespace viewer::window {

// args are the arguments after "view". Returns the process exit code.
int viewCommand(std::span<const std::string> args);

}  // namespace viewer::window
