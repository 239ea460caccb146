// An indexed triangle mesh: what meshing produces, the writers write and compare reads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "primitives/base/GroupByKey.h"
#include "primitives/base/Math.h"

namespace csg {

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // unit, one per position; may be empty for a loaded mesh
    // Corners in counter-clockwise order seen from outside (the normal by the right-hand rule
    // points out of the solid).
    std::vector<std::array<uint32_t, 3>> triangles;
    // One per triangle: the Tags::material of the leaf whose surface the triangle follows.
    // May be empty for a loaded mesh.
    std::vector<uint32_t> triangleMaterial;

    bool empty() const { return triangles.empty(); }
};

// Per vertex, the triangles that use it, in triangle order (a triangle that repeats a vertex is
// listed once per corner there).
inline Grouped<uint32_t> trianglesByVertex(const TriangleMesh& mesh) {
    return groupByKey<uint32_t>(mesh.positions.size(), [&](auto emit) {
        for (size_t t = 0; t < mesh.triangles.size(); ++t)
            for (const uint32_t v : mesh.triangles[t]) emit(v, static_cast<uint32_t>(t));
    });
}

}  // namespace csg
