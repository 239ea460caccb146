// Bounding volume hierarchy over a set of boxes (a union's children): built as a binary tree by
// the binned surface area heuristic, then collapsed into a 4-wide tree (BvhNode) whose four
// slot boxes are tested in one go.
#pragma once

#include <span>
#include <vector>

#include "csg/Compiled.h"

namespace csg {

// No BVH is deeper than this (2^48 leaves would be needed to reach it by median splits); the
// wide tree is no deeper than the binary one it is collapsed from.
inline constexpr int kBvhMaxDepth = 64;
// A leaf slot holds at most this many children (more only where their centres coincide).
inline constexpr uint32_t kBvhMaxLeafCount = 4;

// Builds a BVH over items (indices into itemNodes, whose bounds are finite and non-empty; at
// least two), appending its nodes to `nodes`, and reorders `items` so every leaf slot covers a
// contiguous range of it, expressed relative to `itemsOffset` (the range's position in the
// scene's children array). Returns the root node index.
uint32_t buildBvh(std::span<uint32_t> items, const std::vector<CompiledNode>& itemNodes,
                  uint32_t itemsOffset, std::vector<BvhNode>& nodes);

}  // namespace csg
