// The lecture's two spatial subdivisions (primitives/base/Accel.h) over a set of boxes: a
// union's bounded children (csg/Query.cpp walks them) or a mesh's triangles
// (primitives/Polyhedron.cpp). A cell lists every item whose box, widened by
// tol::kGridMarginRel of the grid's size, overlaps the closed cell, so a ray whose walk rounds
// into a neighbouring cell near a face still meets the item. Items are numbered from an offset
// the caller gives: positions in Scene::children_ for a union (one per child of every union,
// so they double as the mailbox's index), triangle indices for a mesh.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "primitives/base/Bounds.h"

namespace csg {

// A uniform grid: res[0] x res[1] x res[2] cells of one size over box, cell (i, j, k) at index
// i + res[0] * (j + res[1] * k), listing items[cellStart[c], cellStart[c + 1]).
struct UniformGrid {
    Bounds3 box;
    Vec3 cellSize{1.0};
    Vec3 invCellSize{1.0};
    int res[3] = {1, 1, 1};
    std::vector<uint32_t> cellStart;
    std::vector<uint32_t> items;

    size_t bytes() const { return sizeof(*this) + 4 * (cellStart.capacity() + items.capacity()); }
};

// A non-uniform grid: the box halved along x, y, z in turn (the lecture's subdivision) until a
// cell lists at most a few children or a depth limit is met (Grid.cpp). A node is
// either a leaf cell (items[first, first + count)) or a halving at `split` on `axis`, its lower
// half at `first` and its upper half at first + 1.
struct HalvingGrid {
    struct Cell {
        double split = 0.0;
        uint32_t first = 0;
        uint32_t count = 0;
        uint8_t axis = 0;
        bool leaf = true;
    };
    Bounds3 box;
    std::vector<Cell> cells;  // cells[0] is the whole box
    std::vector<uint32_t> items;

    size_t bytes() const {
        return sizeof(*this) + sizeof(Cell) * cells.capacity() + 4 * items.capacity();
    }
};

// Amanatides and Woo's step through a uniform grid: the cell holding the ray's entry point,
// then, one step at a time, the neighbour across the face the ray crosses first (the least of
// the three next face crossings tNext). A face is computed from the cell index each time
// (lo + i * size), never accumulated, so its rounding does not grow along the walk.
struct GridCursor {
    int cell[3];
    int step[3];      // +1, -1, or 0 on an axis the ray does not move along
    double tNext[3];  // t of the next face crossed on each axis (infinite where step is 0)

    // Starts in the cell holding o + tIn d, clamped into the grid (tIn finite).
    GridCursor(const UniformGrid& g, const Vec3& o, const Vec3& d, const Vec3& invD, double tIn) {
        const Vec3 entry = o + tIn * d;
        for (int a = 0; a < 3; ++a) {
            // (A NaN ray starts in cell 0 and, with no step, ends there.)
            const double at = std::floor((entry[a] - g.box.lo[a]) * g.invCellSize[a]);
            cell[a] = at >= 0.0 ? static_cast<int>(std::min(at, g.res[a] - 1.0)) : 0;
            step[a] = d[a] > 0.0 ? 1 : (d[a] < 0.0 ? -1 : 0);
            tNext[a] = faceAhead(g, o, invD, a);
        }
    }

    size_t index(const UniformGrid& g) const {
        return static_cast<size_t>(cell[0]) +
               static_cast<size_t>(g.res[0]) *
                   (static_cast<size_t>(cell[1]) +
                    static_cast<size_t>(g.res[1]) * static_cast<size_t>(cell[2]));
    }

    // Moves to the next cell, entered at tEnter; false (cell unchanged) when the ray leaves
    // the grid instead. Ties go to x, then y, then z.
    bool advance(const UniformGrid& g, const Vec3& o, const Vec3& invD, double& tEnter) {
        const int a =
            tNext[0] <= tNext[1] ? (tNext[0] <= tNext[2] ? 0 : 2) : (tNext[1] <= tNext[2] ? 1 : 2);
        if (step[a] == 0) return false;  // all three infinite
        const int next = cell[a] + step[a];
        if (next < 0 || next >= g.res[a]) return false;
        tEnter = tNext[a];
        cell[a] = next;
        tNext[a] = faceAhead(g, o, invD, a);
        return true;
    }

private:
    double faceAhead(const UniformGrid& g, const Vec3& o, const Vec3& invD, int a) const {
        if (step[a] == 0) return kInfinity;
        const int face = cell[a] + (step[a] > 0 ? 1 : 0);
        return (g.box.lo[a] + face * g.cellSize[a] - o[a]) * invD[a];
    }
};

// Both over boxes (finite, non-empty, at least one); box i is item itemsOffset + i.
UniformGrid buildUniformGrid(std::span<const Bounds3> boxes, uint32_t itemsOffset);
HalvingGrid buildHalvingGrid(std::span<const Bounds3> boxes, uint32_t itemsOffset);

// --accel auto: a union of at least kAutoGridMinItems bounded children gets a uniform grid
// when its items fill at least half the grid's cells (gridPays: spread evenly, as in a layer
// or a field of parts), and the SAH BVH otherwise (a mesh's faces keep the SAH: Polyhedron.cpp).
// bench/README.md ("Spatial structures"): on evenly spread spheres from 10^4 up the grid traces
// as fast as the SAH or faster (shadow rays by 10-30 %) with a seventh of the memory and a third
// of the build time; on clustered ones the SAH is 2-5x faster; below 10^4 the two are level
// (csg_grid's 1000 parts: SAH by ~4 %).
inline constexpr size_t kAutoGridMinItems = 4096;
bool gridPays(const UniformGrid& grid);

// The walks. Both take the ray's range [tIn, tOut] inside the grid's box (finite) and call
// cell(items, count) for each cell the ray enters, nearest first, until cell returns false
// (then they return false) or the next cell begins past t1, which cell may lower; `visits`
// counts the cells entered (and, for the halving grid, the halvings passed).

// Amanatides and Woo's walk of a uniform grid. (The next cell's entry is widened as the slab
// test widens its ends: nothing in a cell that begins past t1 can come before it.)
template <class Cell>
bool walkUniformGrid(const UniformGrid& g, const Vec3& o, const Vec3& d, const Vec3& invD,
                     double tIn, double tOut, double& t1, uint64_t& visits, Cell&& cell) {
    GridCursor cursor(g, o, d, invD, tIn);
    for (;;) {
        ++visits;
        const size_t c = cursor.index(g);
        const uint32_t first = g.cellStart[c];
        if (!cell(g.items.data() + first, g.cellStart[c + 1] - first)) return false;
        double cellIn;
        if (!cursor.advance(g, o, invD, cellIn)) return true;
        if (std::min(cellIn * (1.0 - tol::kSlabWiden), cellIn * (1.0 + tol::kSlabWiden)) >
            std::min(t1, tOut))
            return true;
    }
}

// A non-uniform grid walked as an octree: each halving the ray crosses is entered on the near
// side first, the far side kept with the range past the plane (a front-to-back walk of the
// lecture's cells, without pushing exit points).
template <class Cell>
bool walkHalvingGrid(const HalvingGrid& g, const Vec3& o, const Vec3& invD, double tIn, double tOut,
                     double& t1, uint64_t& visits, Cell&& cell) {
    struct Pending {
        uint32_t cell;
        double tIn, tOut;
    };
    Pending todo[64];  // deeper than any grid (Grid.cpp, kHalvingMaxDepth)
    int pending = 0;
    uint32_t at = 0;
    for (;;) {
        // Down to the leaf cell where [tIn, tOut] begins.
        while (!g.cells[at].leaf) {
            ++visits;
            const HalvingGrid::Cell& c = g.cells[at];
            const int a = c.axis;
            const double tSplit = (c.split - o[a]) * invD[a];
            // The half the ray runs through first; d = +-0 counts by the sign of 1 / d, so a
            // ray in a plane of the axis stays in the half holding its origin.
            const uint32_t nearHalf = c.first + (invD[a] >= 0.0 ? 0 : 1);
            const uint32_t farHalf = c.first + (invD[a] >= 0.0 ? 1 : 0);
            const double lo =
                std::min(tSplit * (1.0 - tol::kSlabWiden), tSplit * (1.0 + tol::kSlabWiden));
            const double hi =
                std::max(tSplit * (1.0 - tol::kSlabWiden), tSplit * (1.0 + tol::kSlabWiden));
            if (lo > tOut) {
                at = nearHalf;
            } else if (hi < tIn) {
                at = farHalf;
            } else if (std::isnan(tSplit)) {  // the ray lies in the plane: both halves
                todo[pending++] = {farHalf, tIn, tOut};
                at = nearHalf;
            } else {
                todo[pending++] = {farHalf, std::max(tIn, lo), tOut};
                at = nearHalf;
                tOut = std::min(tOut, hi);
            }
        }
        ++visits;
        const HalvingGrid::Cell& leaf = g.cells[at];
        if (!cell(g.items.data() + leaf.first, leaf.count)) return false;
        // The next pending cell that begins before t1 (lowered since it was pushed).
        for (;;) {
            if (pending == 0) return true;
            const Pending& next = todo[--pending];
            if (next.tIn > t1) continue;
            at = next.cell;
            tIn = next.tIn;
            tOut = next.tOut;
            break;
        }
    }
}

}  // namespace csg
