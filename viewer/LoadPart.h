// The first step of every subcommand that reads a part: evaluate the file (io/), report its
// diagnostics, and compile the tree into a queryable scene (csg/).
#pragma once

#include "csg/Scene.h"
#include "io/Model.h"
#include "viewer/Cli.h"
#include "viewer/Report.h"

namespace viewer {

struct LoadedPart {
    io::Model model;
    csg::Scene scene;
};

// Returns kExitOk and fills part, or the exit code of the failure after reporting it:
// kExitIo when the part file cannot be read, kExitBadModel for errors in the part (including
// a csg::CompileError, reported at the offending node's statement).
int loadPart(const CommonOptions& options, Report& report, LoadedPart& part);

}  // namespace viewer
