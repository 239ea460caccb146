// The per-format halves of io/mesh/MeshFile.h.
#pragma once

#include <charconv>
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
std::optional<std::string> writeStl(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh, bool ascii);
std::optional<std::string> write3mf(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh,
                                    const std::vector<Material>& materials);

// Appends the shortest text that reads back as exactly value (std::to_chars): a float's
// corner coordinates round-trip, integers are plain digits.
template <class T>
void appendNumber(std::string& out, T value) {
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, end);
}

// The parsers of a file's bytes return positions as written (not welded: parseMesh welds) and
// polygons (glTF: triangles), every position measurable (below).
PolygonMeshReadResult parseObj(std::string_view text);
PolygonMeshReadResult parseStl(std::string_view bytes);
PolygonMeshReadResult parseOff(std::string_view text);
PolygonMeshReadResult parse3mf(std::string_view bytes);
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
