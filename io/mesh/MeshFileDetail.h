// The per-format halves of io/mesh/MeshFile.h.
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "io/mesh/MeshFile.h"
#include "primitives/base/Tolerances.h"

namespace io::detail {

std::optional<std::string> writeObj(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh);
std::optional<std::string> writeGltf(const std::filesystem::path& file,
                                     const csg::TriangleMesh& mesh,
                                     const std::vector<Material>& materials, bool binary);

// The parsers of a file's bytes return positions as written (not welded: parseMesh welds) and
// polygons (glTF: triangles), every position measurable (below).
PolygonMeshReadResult parseObj(std::string_view text);
PolygonMeshReadResult parseStl(std::string_view bytes);
PolygonMeshReadResult parseOff(std::string_view text);
MeshReadResult parseGltf(std::string_view bytes, bool binary, const std::filesystem::path& baseDir);

// Whether a coordinate read can be measured: finite and within ±tol::kMeshCoordinateMax (NaN
// compares false).
inline bool measurable(double c) {
    return std::abs(c) <= csg::tol::kMeshCoordinateMax;
}
inline bool measurable(const csg::Vec3& p) {
    return measurable(p.x) && measurable(p.y) && measurable(p.z);
}
// The error for a coordinate that is not.
inline const char* const kUnmeasurableCoordinate =
    "a coordinate that is not a finite number within ±1e30 cannot be measured";
static_assert(csg::tol::kMeshCoordinateMax == 1e30, "kUnmeasurableCoordinate states it");

}  // namespace io::detail
