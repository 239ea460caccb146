// A whole file read into memory as bytes, for the part language's sources and the mesh
// readers; each caller words its own error.
#pragma once

#include <filesystem>
#include <string>

namespace csg {

enum class ReadFailure { None, IsDirectory, CannotOpen, CannotRead };

// The bytes of path (empty for an empty file), or why not.
ReadFailure readWholeFile(const std::filesystem::path& path, std::string& bytes);

}  // namespace csg
