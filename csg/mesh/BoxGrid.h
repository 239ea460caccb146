// A uniform grid of cubic cells over 3D space, hashed (only cells something touches take
// memory), holding ids by axis-aligned box: an id is listed, with its box, in every cell its box
// overlaps. It answers "which ids have a box overlapping this one" for boxes that change one at
// a time (the triangles of a mesh being decimated, Decimate.cpp), where a BVH would have to be
// refitted or rebuilt. Each cell keeps its ids' boxes (in floats, rounded outward), so a query
// rejects most of them without touching the caller's data for each id.
#pragma once

#include <cstdint>
#include <vector>

#include "primitives/base/Bounds.h"

namespace csg {

class BoxGrid {
public:
    // Cells of edge `cell` (world units, > 0) with a corner at origin. Coordinates more than
    // ~2^20 cells from origin share the outermost cells (still correct, only slower).
    BoxGrid(const Vec3& origin, double cell);

    // Lists id with box in every cell box overlaps. An id may be inserted under several boxes;
    // each insert needs its own remove.
    void insert(uint32_t id, const Bounds3& box);
    // Unlists id from the cells of box, which must be a box it was inserted with.
    void remove(uint32_t id, const Bounds3& box);

    // An id and its box, rounded outward to floats.
    struct Entry {
        float lo[3], hi[3];
        uint32_t id;
        bool overlaps(const Bounds3& b) const {
            return lo[0] <= b.hi[0] && hi[0] >= b.lo[0] && lo[1] <= b.hi[1] && hi[1] >= b.lo[1] &&
                   lo[2] <= b.hi[2] && hi[2] >= b.lo[2];
        }
    };

    // Calls fn(entry) for the ids whose box overlaps box (every such id, and a few more whose
    // boxes miss it by float rounding; an id listed in several cells box overlaps comes once per
    // cell: the caller removes duplicates).
    template <class Fn>
    void forEachNear(const Bounds3& box, Fn&& fn) const {
        forEachCellKey(box, [&](uint64_t cell) {
            const uint32_t slot = find(cell);
            if (slot == kEmpty) return;
            for (const Entry& e : lists_[slots_[slot].list])
                if (e.overlaps(box)) fn(e);
        });
    }

private:
    struct Range {
        int32_t lo[3], hi[3];
    };
    struct Slot {
        uint64_t key;
        uint32_t list;  // index into lists_
    };
    static constexpr uint32_t kEmpty = UINT32_MAX;

    static Entry entry(uint32_t id, const Bounds3& box);
    Range range(const Bounds3& box) const;
    // Calls fn(key) for every cell box overlaps.
    template <class Fn>
    void forEachCellKey(const Bounds3& box, Fn&& fn) const {
        const Range r = range(box);
        for (int32_t z = r.lo[2]; z <= r.hi[2]; ++z)
            for (int32_t y = r.lo[1]; y <= r.hi[1]; ++y)
                for (int32_t x = r.lo[0]; x <= r.hi[0]; ++x) fn(key(x, y, z));
    }
    static uint64_t key(int32_t x, int32_t y, int32_t z);
    // The slot holding key, or kEmpty.
    uint32_t find(uint64_t key) const;
    // The list of key's cell, made empty if it had none.
    std::vector<Entry>& listOf(uint64_t key);
    void grow();

    Vec3 origin_;
    double inverseCell_;
    // Open addressing with linear probing; a slot whose list is kEmpty is free. Cells are never
    // unlisted (an emptied cell keeps its empty list), so probing needs no tombstones.
    std::vector<Slot> slots_;
    std::vector<std::vector<Entry>> lists_;
};

}  // namespace csg
