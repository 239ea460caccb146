#include "csg/Bvh.h"

namespace csg {

uint32_t buildBvh(std::span<uint32_t> items, const std::vector<CompiledNode>& itemNodes,
                  uint32_t itemsOffset, std::vector<BvhNode>& nodes, BvhMethod method) {
    // One child per leaf (more only where no split pays): the leaf's box is then the child's
    // own, so the ray loop does not test the child's bounds again
    // (CompiledNode::boundsImplied); two per leaf cost more instructions on csg_grid
    // (bench/README.md, one child per BVH leaf). A box test costs half a child's evaluation.
    const BvhBuildOptions kUnionOptions{.maxLeafItems = 1, .traversalCost = 0.5, .method = method};
    std::vector<Bounds3> boxes(items.size());
    for (size_t i = 0; i < items.size(); ++i) boxes[i] = itemNodes[items[i]].bounds;
    std::vector<uint32_t> order;
    const uint32_t root = buildWideBvh(boxes, order, itemsOffset, kUnionOptions, nodes);
    const std::vector<uint32_t> given(items.begin(), items.end());
    for (size_t i = 0; i < items.size(); ++i) items[i] = given[order[i]];
    return root;
}

}  // namespace csg
