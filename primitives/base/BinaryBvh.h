// The binary tree every hierarchy builder of WideBvh.cpp produces before the 4-wide collapse
// (private to primitives/base). Layout: preorder, so an interior node's left child follows at
// index + 1 and its right child is at firstOrRight; a leaf covers the items
// order[firstOrRight, firstOrRight + count) of the build's order array.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "primitives/base/Bounds.h"

namespace csg {

struct BinaryNode {
    Bounds3 box;
    uint32_t firstOrRight = 0;
    uint32_t count = 0;  // 0: interior
    int axis = 0;        // an interior node's split axis: its left child lies toward -axis
};

// The lecture's median cut: the longest side of a node's box, its items sorted by their lower
// bound on that side (ties by index), the first half left. Leaves hold at most maxLeafItems.
// order holds the item indices (any permutation) and is reordered into leaf order.
std::vector<BinaryNode> buildMedianCut(std::span<const Bounds3> boxes, std::span<uint32_t> order,
                                       uint32_t maxLeafItems);

// Goldsmith and Salmon's insertion: one leaf per item, each inserted (in a fixed pseudo-random
// order) as the sibling of the node along one greedy path down the tree where the sum of the
// areas it enlarges is least, then the boxes above it refitted. order as above. Falls back to
// the median cut when the tree would be deeper than kBvhMaxDepth (never seen in practice).
std::vector<BinaryNode> buildGoldsmithSalmon(std::span<const Bounds3> boxes,
                                             std::span<uint32_t> order, uint32_t maxLeafItems);

}  // namespace csg
