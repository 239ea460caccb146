// OpenSCAD 2021's Grid2d<std::vector<int>> at GRID_COARSE (src/grid.h), which its DXF reader
// snaps every end of every line to and chains lines through (io/DxfFile.h). Internal to the
// DXF reader (DxfFile.cpp, DxfPaths.cpp).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/DxfFile.h"
#include "primitives/base/Math.h"

namespace io::detail {

class DxfGrid {
public:
    // GRID_COARSE: 1/1024, exact in binary, so a node's coordinates are exact multiples of it.
    static constexpr double kResolution = 0x1p-10;
    // The numbers of the edges with an end at the node. OpenSCAD also files the ends of block
    // lines here, under the number the next drawing line will get: those entries may name an
    // edge that has no end at the node, or no edge at all (a number >= the edge count).
    using Cell = std::vector<int64_t>;

    // Grid2d::align: p moves to its node when the node exists, else to the nearest existing
    // node of the 8 neighbouring cells (OpenSCAD's scan order and tie rule: the loop moves the
    // centre it measures from as it finds nodes), else to its own node; that node is created.
    // |p| must stay below 2^52 / 1024 so the node number is exact.
    Cell& align(csg::Vec2& p) {
        int64_t ix = static_cast<int64_t>(std::round(p.x / kResolution));
        int64_t iy = static_cast<int64_t>(std::round(p.y / kResolution));
        if (!cells_.contains(Key{ix, iy})) {
            int dist = 10;
            for (int64_t jx = ix - 1; jx <= ix + 1; ++jx) {
                for (int64_t jy = iy - 1; jy <= iy + 1; ++jy) {
                    if (!cells_.contains(Key{jx, jy})) continue;
                    const int d = int(std::llabs(ix - jx) + std::llabs(iy - jy));
                    if (d < dist) {
                        dist = d;
                        ix = jx;
                        iy = jy;
                    }
                }
            }
        }
        p = csg::Vec2(double(ix) * kResolution, double(iy) * kResolution);
        return cells_[Key{ix, iy}];
    }

    // f(Cell&) for every node (references stay valid: the map is node-based).
    template <class F>
    void forEachCell(F&& f) {
        for (auto& [key, cell] : cells_) f(cell);
    }

private:
    struct Key {
        int64_t x, y;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const noexcept {
            return std::hash<int64_t>{}(k.x) * 0x9E3779B97F4A7C15ull ^ std::hash<int64_t>{}(k.y);
        }
    };
    std::unordered_map<Key, Cell, KeyHash> cells_;
};

// OpenSCAD's path extraction (the two loops after parsing in DxfData::DxfData, then
// fixup_path_direction) over drawing.edges, whose start and finish lie in the cells ends[k][0]
// and ends[k][1] of grid: fills drawing.paths. An error (a message) when the chaining would
// take unreasonable work (hundreds of thousands of edges meeting at one point).
std::optional<std::string> chainPaths(DxfDrawing& drawing, DxfGrid& grid,
                                      const std::vector<std::array<DxfGrid::Cell*, 2>>& ends);

}  // namespace io::detail
