// Builds the uniform and non-uniform grids of Grid.h, and judges them for --accel auto.
#include "primitives/base/Grid.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/GroupByKey.h"

namespace csg {
namespace {

// Cells per child of a uniform grid: the usual choice of a few cells per object (fewer
// leaves long empty walks across sparse regions, more lists each child in more cells).
constexpr double kCellsPerItem = 2.0;
// No axis is cut finer than this, and no grid has more cells than kMaxCellsPerItem per child:
// a flat or thin scene would otherwise spend its cells on an axis it barely spans.
constexpr int kMaxResolution = 4096;
constexpr double kMaxCellsPerItem = 8.0;

// A non-uniform grid cell of at most this many children is not halved further.
constexpr uint32_t kHalvingLeafItems = 4;
// Nor one halved this many times along each axis beyond what n / kHalvingLeafItems cubic cells
// would take: the lecture's depth limit. Without it, a cell straddling a child's face keeps
// halving toward the face (each halving drops the children on the other side of the face),
// so the faces of overlapping children would be refined without end.
constexpr int kHalvingExtraLevels = 2;
// No deeper than this in all (the walk's stack in Query.cpp holds 64).
constexpr int kHalvingMaxDepth = 60;

Bounds3 hullOf(std::span<const Bounds3> boxes) {
    Bounds3 box;
    for (const Bounds3& b : boxes) box.extend(b);
    return box;
}

// tol::kGridMarginRel of the box's size.
double marginOf(const Bounds3& box) {
    const Vec3 size = glm::max(glm::max(glm::abs(box.lo), glm::abs(box.hi)), box.extent());
    // (Not zero, so a grid over one point still has cells of some size.)
    return std::max(tol::kGridMarginRel * std::max({size.x, size.y, size.z}), 1e-300);
}

Bounds3 widened(const Bounds3& b, double margin) {
    return {b.lo - Vec3(margin), b.hi + Vec3(margin)};
}

struct HalvingBuilder {
    std::span<const Bounds3> boxes;  // already widened
    uint32_t itemsOffset;
    int maxDepth;
    HalvingGrid& grid;

    // Halves along x, y, z in turn from the axis after `previous`, skipping an axis whose side
    // is already below half the longest (a flat scene would otherwise spend a third of its
    // depth on its thin axis), until a cell lists few children or the depth limit is met.
    void build(uint32_t cell, const Bounds3& box, std::vector<uint32_t>& list, int depth,
               int previous) {
        if (list.size() <= kHalvingLeafItems || depth >= maxDepth) {
            grid.cells[cell].first = static_cast<uint32_t>(grid.items.size());
            grid.cells[cell].count = static_cast<uint32_t>(list.size());
            for (uint32_t i : list) grid.items.push_back(itemsOffset + i);
            return;
        }
        const Vec3 side = box.extent();
        const double longest = std::max({side.x, side.y, side.z});
        int axis = (previous + 1) % 3;
        while (side[axis] < 0.5 * longest) axis = (axis + 1) % 3;
        const double split = 0.5 * (box.lo[axis] + box.hi[axis]);
        std::vector<uint32_t> lower, upper;
        for (uint32_t i : list) {
            if (boxes[i].lo[axis] <= split) lower.push_back(i);
            if (boxes[i].hi[axis] >= split) upper.push_back(i);
        }
        std::vector<uint32_t>().swap(list);  // free the parent's list before recursing
        const uint32_t first = static_cast<uint32_t>(grid.cells.size());
        grid.cells.resize(grid.cells.size() + 2);
        HalvingGrid::Cell& c = grid.cells[cell];
        c.leaf = false;
        c.axis = static_cast<uint8_t>(axis);
        c.split = split;
        c.first = first;
        Bounds3 lowerBox = box, upperBox = box;
        lowerBox.hi[axis] = split;
        upperBox.lo[axis] = split;
        build(first, lowerBox, lower, depth + 1, axis);
        build(first + 1, upperBox, upper, depth + 1, axis);
    }
};

}  // namespace

UniformGrid buildUniformGrid(std::span<const Bounds3> boxes, uint32_t itemsOffset) {
    UniformGrid grid;
    const Bounds3 hull = hullOf(boxes);
    const double margin = marginOf(hull);
    grid.box = widened(hull, margin);
    const Vec3 extent = grid.box.extent();

    // Cells about cubic, kCellsPerItem per child, on the box's proportions.
    const double n = static_cast<double>(boxes.size());
    const double perLength = std::cbrt(kCellsPerItem * n / (extent.x * extent.y * extent.z));
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) {
        grid.res[a] = static_cast<int>(std::clamp(std::floor(extent[a] * perLength), 1.0,
                                                  static_cast<double>(kMaxResolution)));
        cells *= grid.res[a];
    }
    // A box flat on an axis gives that axis one cell and the cube root too few on the others:
    // spread the missing factor over the axes that can take it, within the caps.
    for (int round = 0; round < 2 && cells < kCellsPerItem * n / 2; ++round) {
        int free = 0;
        for (int a = 0; a < 3; ++a) free += grid.res[a] > 1 ? 1 : 0;
        if (free == 0) break;
        const double factor = std::pow(kCellsPerItem * n / cells, 1.0 / free);
        cells = 1.0;
        for (int a = 0; a < 3; ++a) {
            if (grid.res[a] > 1)
                grid.res[a] = static_cast<int>(std::clamp(std::floor(grid.res[a] * factor), 1.0,
                                                          static_cast<double>(kMaxResolution)));
            cells *= grid.res[a];
        }
    }
    while (cells > kMaxCellsPerItem * n + 64) {
        const int a = grid.res[0] >= grid.res[1] ? (grid.res[0] >= grid.res[2] ? 0 : 2)
                                                 : (grid.res[1] >= grid.res[2] ? 1 : 2);
        cells /= grid.res[a];
        grid.res[a] = std::max(1, grid.res[a] / 2);
        cells *= grid.res[a];
    }
    for (int a = 0; a < 3; ++a) {
        grid.cellSize[a] = extent[a] / grid.res[a];
        grid.invCellSize[a] = grid.res[a] / extent[a];
    }

    // The cell range of each widened box, per axis: closed cells, so a box ending on a face
    // lists in both cells.
    const auto range = [&](const Bounds3& b, int(&lo)[3], int(&hi)[3]) {
        for (int a = 0; a < 3; ++a) {
            const double scale = grid.invCellSize[a];
            lo[a] = std::clamp(
                static_cast<int>(std::floor((b.lo[a] - margin - grid.box.lo[a]) * scale)), 0,
                grid.res[a] - 1);
            hi[a] = std::clamp(
                static_cast<int>(std::floor((b.hi[a] + margin - grid.box.lo[a]) * scale)), 0,
                grid.res[a] - 1);
        }
    };
    const size_t cellCount = static_cast<size_t>(cells);
    const auto forEachCell = [&](const Bounds3& b, auto&& f) {
        int lo[3], hi[3];
        range(b, lo, hi);
        for (int k = lo[2]; k <= hi[2]; ++k)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int i = lo[0]; i <= hi[0]; ++i)
                    f(static_cast<size_t>(i) +
                      static_cast<size_t>(grid.res[0]) *
                          (static_cast<size_t>(j) + static_cast<size_t>(grid.res[1]) * k));
    };
    // Each cell's items, in item order.
    Grouped<uint32_t> byCell = groupByKey<uint32_t>(cellCount, [&](auto&& emit) {
        for (uint32_t i = 0; i < boxes.size(); ++i)
            forEachCell(boxes[i], [&](size_t c) { emit(c, itemsOffset + i); });
    });
    grid.cellStart = std::move(byCell.start);
    grid.items = std::move(byCell.values);
    return grid;
}

bool gridPays(const UniformGrid& grid) {
    size_t filled = 0;
    const size_t cells = grid.cellStart.size() - 1;
    for (size_t c = 0; c < cells; ++c) filled += grid.cellStart[c + 1] > grid.cellStart[c];
    return static_cast<double>(filled) >= 0.5 * static_cast<double>(cells);
}

HalvingGrid buildHalvingGrid(std::span<const Bounds3> boxes, uint32_t itemsOffset) {
    HalvingGrid grid;
    const Bounds3 hull = hullOf(boxes);
    const double margin = marginOf(hull);
    grid.box = widened(hull, margin);
    std::vector<Bounds3> wide(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) wide[i] = widened(boxes[i], margin);
    std::vector<uint32_t> all(boxes.size());
    for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    // Halvings per axis for cubic cells of kHalvingLeafItems children, plus the extra levels.
    const double cellsPerSide =
        std::cbrt(std::max(1.0, static_cast<double>(boxes.size()) / kHalvingLeafItems));
    const int levels = static_cast<int>(std::ceil(std::log2(cellsPerSide))) + kHalvingExtraLevels;
    const int maxDepth = std::min(kHalvingMaxDepth, 3 * levels);
    grid.cells.resize(1);
    HalvingBuilder{wide, itemsOffset, maxDepth, grid}.build(0, grid.box, all, 0, 2);
    grid.cells.shrink_to_fit();
    grid.items.shrink_to_fit();
    return grid;
}

}  // namespace csg
