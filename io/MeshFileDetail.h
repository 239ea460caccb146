// The per-format halves of io/MeshFile.h.
#pragma once

#include "io/MeshFile.h"

namespace io::detail {

std::optional<std::string> writeObj(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh);
std::optional<std::string> writeGltf(const std::filesystem::path& file,
                                     const csg::TriangleMesh& mesh,
                                     const std::vector<Material>& materials, bool binary);
MeshReadResult readWithOpenMesh(const std::filesystem::path& file);
MeshReadResult readGltf(const std::filesystem::path& file, bool binary);

}  // namespace io::detail
