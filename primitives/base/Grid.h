// The lecture's two spatial subdivisions over a union's bounded children (csg/Accel.h), built
// here and walked by csg/Query.cpp. A cell lists every child whose box, widened by
// tol::kGridMarginRel of the grid's size, overlaps the closed cell, so a ray whose walk
// rounds into a neighbouring cell near a face still meets the child. Items are positions in
// Scene::children_ (one per child of every union, so they double as the mailbox's index).
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

// Both over the boxes of items (positions itemsOffset, itemsOffset + 1, ... of
// Scene::children_): finite, non-empty, at least one.
UniformGrid buildUniformGrid(std::span<const Bounds3> boxes, uint32_t itemsOffset);
HalvingGrid buildHalvingGrid(std::span<const Bounds3> boxes, uint32_t itemsOffset);

}  // namespace csg
