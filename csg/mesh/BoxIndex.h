// A fixed set of axis-aligned boxes, indexed by the shared 4-wide BVH (primitives/base/
// WideBvh.h), answering "which boxes overlap this one". For sets that do not change once built
// (the faces of a part's exact boundary, PolyhedralBoundary.cpp), where BoxGrid, made for boxes
// that change one at a time, lists a large box in every cell it covers and tests it once per
// cell a query shares with it.
#pragma once

#include <cstdint>
#include <vector>

#include "primitives/base/Bounds.h"
#include "primitives/base/WideBvh.h"

namespace csg {

class BoxIndex {
public:
    // Indexes boxes[i] as id i; the index keeps the boxes.
    explicit BoxIndex(std::vector<Bounds3> boxes);

    // Calls fn(id) once for every id whose box overlaps box (closed boxes: touching counts).
    template <class Fn>
    void forEachOverlapping(const Bounds3& box, Fn&& fn) const {
        if (nodes_.empty()) return;
        uint32_t todo[3 * kBvhMaxDepth + 4];
        int pending = 0;
        todo[pending++] = root_;
        while (pending > 0) {
            const BvhNode& node = nodes_[todo[--pending]];
            const unsigned hits = overlapBoxes(node.boxes, box) & node.usedMask();
            for (int k = 0; k < node.slots; ++k) {
                if (!(hits >> k & 1u)) continue;
                if (node.leafCount[k] == 0) {
                    todo[pending++] = node.slot[k];
                    continue;
                }
                for (uint32_t i = node.slot[k]; i < node.slot[k] + node.leafCount[k]; ++i)
                    if (!overlap(boxes_[order_[i]], box).empty()) fn(order_[i]);
            }
        }
    }

private:
    std::vector<Bounds3> boxes_;
    std::vector<uint32_t> order_;
    std::vector<BvhNode> nodes_;
    uint32_t root_ = 0;
};

}  // namespace csg
