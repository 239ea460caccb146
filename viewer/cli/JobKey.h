// The identity of a long job (--resume): a hash of everything that decides its output, so that
// a journal left by another part, another -D or other options is never taken for this job's.
#pragma once

#include <string>
#include <string_view>

#include "viewer/cli/Cli.h"

namespace viewer {

// Sixteen hex digits of a hash over the command's name, the part's path and text (files it
// includes do not count), its -D values, --curves, --polygon-method, `settings` (the command's
// own options that change its output, in any fixed text form), and the running csgray's size
// and modification time: a journal is never taken by another build, whose loops or tiles may
// differ. Options that change only the speed (--threads, --accel, --bounds: every choice
// answers bit for bit alike) stay out, so a job may resume with other threads or on other
// ranks.
std::string jobKey(std::string_view command, const CommonOptions& common,
                   std::string_view settings);

}  // namespace viewer
