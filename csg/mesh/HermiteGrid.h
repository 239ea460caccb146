// Tri-dexel Hermite data of a scene on a rectilinear grid: rays along x, y and z through every
// grid line give, on each grid edge, the exact surface crossings and outward normals.
//
// Notation: a grid node (i, j, k) sits at (x[i], y[j], z[k]), the coordinates of each axis
// ascending; a uniform grid has x[i] = x[0] + h i. Planes added where a wall or gap is thinner
// than a cell (ThinFeatures.h) make some cells thinner than h. A line of axis a is the row of
// nodes that differ only in coordinate a; its ray starts h before node 0 (unit axis direction),
// so node n of the line is at ray parameter t = coords[a][n] - coords[a][0] + h. The edge
// (a, node) joins node and node + e_a. Inside/outside of a node comes from the z lines only,
// so every cell sees one consistent sign per corner.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "csg/Scene.h"
#include "csg/mesh/Distribute.h"

namespace csg {

struct GridSpec {
    double h = 1.0;  // the uniform spacing the grid was made with (world units); no cell is wider
    std::array<std::vector<double>, 3> coords;  // node coordinates per axis, strictly ascending
    std::array<int, 3> nodes{0, 0, 0};          // coords[a].size() (cells = nodes - 1)

    uint64_t nodeCount() const { return uint64_t(nodes[0]) * nodes[1] * nodes[2]; }
    uint64_t cellCount() const { return uint64_t(nodes[0] - 1) * (nodes[1] - 1) * (nodes[2] - 1); }
    Vec3 node(int i, int j, int k) const {
        return {coords[0][size_t(i)], coords[1][size_t(j)], coords[2][size_t(k)]};
    }
    // Ray parameter of node n on a line of axis a (see the notation above).
    double lineT(int a, int n) const {
        return coords[size_t(a)][size_t(n)] - coords[size_t(a)][0] + h;
    }
    // The smallest edge of cell (i, j, k) (its corner with the smallest indices).
    double cellMinWidth(int i, int j, int k) const;
    // Replaces the coordinates of every axis (each sorted and deduplicated here).
    void setCoords(std::array<std::vector<double>, 3> c);
};

// A grid covering bounds with at least a quarter cell of margin on every side, so every node
// on the grid's boundary is outside the solid. The origin is shifted by an irrational fraction
// of h so that grid nodes and lines rarely lie exactly on the axis-aligned faces parts are
// built from (a node on a face has no trustworthy sign). bounds must be finite and non-empty.
GridSpec makeGrid(const Bounds3& bounds, double h);

// An interval along one axis (world coordinates lo < hi) between two crossings of one grid edge
// whose surfaces face each other: a wall or gap thinner than the edge that a grid plane through
// it would resolve.
struct ThinInterval {
    double lo, hi;
};

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
    // one QueryContext per thread; with `distribute`, row by row on the processes of a job
    // (csg/mesh/Distribute.h: the same grid on every one).
    static HermiteGrid cast(const Scene& scene, const GridSpec& spec, int threads,
                            const ItemDistributor* distribute = nullptr);

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
    // Per axis, the thin edges whose two crossings face each other (normals more than
    // tol::kThinFacingCos apart): walls and gaps, not a line grazing a curved surface.
    const std::array<std::vector<ThinInterval>, 3>& thinIntervals() const { return thin_; }

private:
    GridSpec spec_;
    std::vector<uint8_t> inside_;                     // per node, 1 = inside the solid
    std::array<std::vector<Crossing>, 3> crossings_;  // per axis, line by line, ascending t
    std::array<std::vector<uint64_t>, 3> lineStart_;  // per axis, lineCount + 1 offsets
    uint64_t rays_ = 0;
    uint64_t thinEdges_ = 0;
    Vec3 thinAt_{0.0};
    std::array<std::vector<ThinInterval>, 3> thin_;
};

}  // namespace csg
