// `csgray probe`: the whole span list of one ray (--origin, --dir) or of many (--rays), as JSON.
#pragma once

#include <span>
#include <string>

namespace viewer {

// args are the arguments after "probe". Returns the process exit code.
int probeCommand(std::span<const std::string> args);

}  // namespace viewer
