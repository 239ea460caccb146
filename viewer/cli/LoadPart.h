// The first step of every subcommand that reads a part: evaluate the file (io/), report its
// diagnostics, and compile the tree into a queryable scene (csg/).
#pragma once

#include <string_view>

#include "csg/Scene.h"
#include "io/Model.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/Report.h"

namespace viewer {

struct LoadedPart {
    io::Model model;
    csg::Scene scene;
};

// Returns kExitOk and fills part, or the exit code of the failure after reporting it:
// kExitIo when the part file cannot be read, kExitBadModel for errors in the part (including
// a csg::CompileError, reported at the offending node's statement).
int loadPart(const CommonOptions& options, Report& report, LoadedPart& part);

// For commands that need volume (export's mesh, compare's volumes): kExitOk when every leaf is
// a solid, else kExitBadModel after reporting an error at the first surface (a bezier_patch
// with solid=false): a surface has no inside, so there is nothing to mesh or measure. A 2-D
// part (io::Model::twoD) is an error too, as in OpenSCAD.
int requireSolids(const LoadedPart& part, Report& report, std::string_view command);

}  // namespace viewer
