// Tri-dexel Hermite data of a scene on a uniform grid: rays along x, y and z through every
// grid line give, on each grid edge, the exact surface crossings and outward normals.
//
// Notation: a grid node (i, j, k) sits at origin + h (i, j, k). A line of axis a is the row of
// nodes that differ only in coordinate a; its ray starts one cell before node 0, so node n of
// the line is at ray parameter t = (n + 1) h (the ray direction is the unit axis). The edge
// (a, node) joins node and node + e_a. Inside/outside of a node comes from the z lines only,
// so every cell sees one consistent sign per corner.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "csg/Scene.h"

namespace csg {

struct GridSpec {
    Vec3 origin{0.0};
    double h = 1.0;                     // cell edge length (world units)
    std::array<int, 3> nodes{2, 2, 2};  // node count per axis (cells = nodes - 1)

    uint64_t nodeCount() const { return uint64_t(nodes[0]) * nodes[1] * nodes[2]; }
    uint64_t cellCount() const { return uint64_t(nodes[0] - 1) * (nodes[1] - 1) * (nodes[2] - 1); }
    Vec3 node(int i, int j, int k) const { return origin + h * Vec3(i, j, k); }
};

// A grid covering bounds with at least a quarter cell of margin on every side, so every node
// on the grid's boundary is outside the solid. The origin is shifted by an irrational fraction
// of h so that grid nodes and lines rarely lie exactly on the axis-aligned faces parts are
// built from (a node on a face has no trustworthy sign). bounds must be finite and non-empty.
GridSpec makeGrid(const Bounds3& bounds, double h);

// One surface crossing of a grid line.
struct Crossing {
    Vec3 point;         // o + t d, on the exact surface
    Vec3 normal;        // outward unit normal of the solid there
    double t;           // ray parameter (node n of the line is at t = (n + 1) h)
    uint32_t material;  // Tags::material of the hit leaf
};

class HermiteGrid {
public:
    // Casts every line of the three axes through scene with `threads` threads (0: all cores),
    // one QueryContext per thread.
    static HermiteGrid cast(const Scene& scene, const GridSpec& spec, int threads);

    const GridSpec& spec() const { return spec_; }
    bool inside(int i, int j, int k) const {
        return inside_[i + size_t(spec_.nodes[0]) * (j + size_t(spec_.nodes[1]) * k)] != 0;
    }
    // The first crossing on edge (axis, node) within (t(node), t(node + 1)], or nullptr.
    const Crossing* crossing(int axis, std::array<int, 3> node) const;
    uint64_t rays() const { return rays_; }
    // Grid edges that a line crosses more than once (only the first crossing is used): a
    // wall or gap thinner than one cell, which the mesh fuses or loses there. thinAt() is the
    // midpoint of one such pair of crossings (the first in axis, row, line order).
    uint64_t thinEdges() const { return thinEdges_; }
    Vec3 thinAt() const { return thinAt_; }

private:
    GridSpec spec_;
    std::vector<uint8_t> inside_;                     // per node, 1 = inside the solid
    std::array<std::vector<Crossing>, 3> crossings_;  // per axis, line by line, ascending t
    std::array<std::vector<uint64_t>, 3> lineStart_;  // per axis, lineCount + 1 offsets
    uint64_t rays_ = 0;
    uint64_t thinEdges_ = 0;
    Vec3 thinAt_{0.0};
};

}  // namespace csg
