// Data files named in a part (import(), the DXF functions): where OpenSCAD 2021 finds them
// (src/fileutils.cc `lookup_file`).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "io/Evaluator.h"

namespace io {

// The file `written` names in a call at `call`: an absolute name as it is; a relative one
// beside the .scad file that holds the call, else (when only that exists) beside the main file,
// with OpenSCAD's deprecation warning at `at`. The path beside the calling file when neither
// exists, so that errors name where it was expected.
std::filesystem::path lookupDataFile(Evaluator& e, Loc call, Loc at, const std::string& written);

// A file name's extension, lower-cased (".dxf"), by which OpenSCAD picks a reader.
std::string lowerExtension(std::string_view name);

}  // namespace io
