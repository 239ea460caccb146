// The per-format halves of io/MeshFile.h.
#pragma once

#include <string>

#include "io/MeshFile.h"

namespace io::detail {

std::optional<std::string> writeObj(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh);
std::optional<std::string> writeGltf(const std::filesystem::path& file,
                                     const csg::TriangleMesh& mesh,
                                     const std::vector<Material>& materials, bool binary);

// The readers return positions as written (not welded: readMesh welds) and triangles.
MeshReadResult readObj(const std::filesystem::path& file);
MeshReadResult readStl(const std::filesystem::path& file);
MeshReadResult readGltf(const std::filesystem::path& file, bool binary);

// The whole file into bytes; false (result.error and unreadable set) when it cannot be read.
bool readBytes(const std::filesystem::path& file, std::string& bytes, MeshReadResult& result);

}  // namespace io::detail
