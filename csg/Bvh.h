// Binned SAH bounding volume hierarchy over a set of boxes (a union's children).
#pragma once

#include <span>
#include <vector>

#include "csg/Compiled.h"

namespace csg {

// No BVH is deeper than this (2^48 leaves would be needed to reach it by median splits).
inline constexpr int kBvhMaxDepth = 64;

// Builds a BVH over items (indices into itemNodes, whose bounds are finite and non-empty),
// appending its nodes to `nodes`, and reorders `items` so every BVH leaf covers a contiguous range
// of it, expressed relative to `itemsOffset` (the range's position in the scene's children array).
// Returns the root node index.
uint32_t buildBvh(std::span<uint32_t> items, const std::vector<CompiledNode>& itemNodes,
                  uint32_t itemsOffset, std::vector<BvhNode>& nodes);

}  // namespace csg
