// The BVH over a union's bounded children: primitives/base/WideBvh.h's builder with csg's leaf
// size and costs, in the scene's children array.
#pragma once

#include <span>
#include <vector>

#include "csg/Compiled.h"

namespace csg {

// Builds a BVH over items (indices into itemNodes, whose bounds are finite and non-empty; at
// least two), appending its nodes to `nodes`, and reorders `items` so every leaf slot covers a
// contiguous range of it, expressed relative to `itemsOffset` (the range's position in the
// scene's children array). Returns the root node index.
// method: which of the lecture's hierarchies (primitives/base/WideBvh.h).
uint32_t buildBvh(std::span<uint32_t> items, const std::vector<CompiledNode>& itemNodes,
                  uint32_t itemsOffset, std::vector<BvhNode>& nodes,
                  BvhMethod method = BvhMethod::Sah);

}  // namespace csg
