// The spatial structure that organizes the objects of a union and the faces of a mesh
// (--accel): the lecture's three hierarchies, collapsed into the same 4-wide BVH
// (primitives/base/WideBvh.h), and its two spatial subdivisions (primitives/base/Grid.h). The
// span merging of csg/Query.cpp walks each through one call, forEachChild, and does not know
// which it walks; a mesh's crossing search (primitives/Polyhedron.cpp) walks each to gather
// its crossings. Inside a CSG tree the bottom-up node bounds stay as they are; only unions of
// at least four bounded children get a structure.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace csg {

enum class Accel : uint8_t {
    Sah,              // surface area heuristic BVH (the default)
    Median,           // median-cut BVH
    GoldsmithSalmon,  // Goldsmith-Salmon insertion BVH
    Grid,             // uniform grid, Amanatides-Woo walk
    NonUniformGrid,   // recursive halving along x, y, z in turn, walked as an octree
    Auto,             // per union: a uniform grid for large evenly spread ones, else SAH
                      // (gridPays in Grid.h); the SAH over a mesh's faces
};

// The names of --accel, in the enum's order.
inline constexpr std::array<std::string_view, 6> kAccelNames = {
    "sah", "median", "goldsmith-salmon", "grid", "nonuniform-grid", "auto"};

inline std::string_view accelName(Accel accel) {
    return kAccelNames[static_cast<size_t>(accel)];
}

inline std::optional<Accel> parseAccel(std::string_view name) {
    for (size_t i = 0; i < kAccelNames.size(); ++i)
        if (kAccelNames[i] == name) return static_cast<Accel>(i);
    return std::nullopt;
}

}  // namespace csg
