// The one bounding volume hierarchy builder: over a set of boxes (a union's children in csg/, a
// mesh's triangles in primitives/), built as a binary tree by the binned surface area heuristic,
// then collapsed into a 4-wide tree (BvhNode) whose four slot boxes are tested in one go
// (Bounds4.h). Each client walks the tree its own way; the tree and its build are shared.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "primitives/base/Bounds.h"
#include "primitives/base/Bounds4.h"

namespace csg {

// No BVH is deeper than this: the SAH stops kBvhMedianLevels short of it and halves after, so
// a tree over up to 2^kBvhMedianLevels items (times the leaf size) fits; the wide tree is no
// deeper than the binary one it is collapsed from.
inline constexpr int kBvhMaxDepth = 64;
inline constexpr int kBvhMedianLevels = 24;

// A node of a 4-wide BVH: up to four slots, each a child node or a leaf, a run of the items.
// The slots' boxes are stored by axis and slot, so that one clipToBoxes (Bounds4.h) tests all
// four. A node is 128 bytes (125 of fields), two cache lines, aligned so that it never
// straddles a third.
struct alignas(64) BvhNode {
    Bounds4 boxes;              // slot k's box (rounded out to floats) is lane k; unused
                                // lanes are masked out
    uint32_t slot[4] = {};      // leaf: itemsOffset + the index of its first item in the order
                                // the build leaves; else the child node's index
    uint8_t leafCount[4] = {};  // items in a leaf slot (1 .. 4 * maxLeafItems); 0: a node
    uint8_t slots = 0;          // slots in use (1..4), the first ones
    // Per direction octant (bit a: d[a] < 0), the slots nearest first, two bits each: the
    // order the binary tree's splits give, so a walk needs no sort.
    uint8_t order[8] = {};

    unsigned usedMask() const { return (1u << slots) - 1u; }
};
static_assert(sizeof(BvhNode) == 128);

// The octant of a direction, as BvhNode::order is indexed: bit a set when d[a] < 0.
inline unsigned octantOf(const Vec3& d) {
    return unsigned(d.x < 0.0) | unsigned(d.y < 0.0) << 1 | unsigned(d.z < 0.0) << 2;
}

// How the binary tree is built before it is collapsed into 4-wide nodes: the lecture's three
// hierarchies. The walk and the node layout are the same for all three.
enum class BvhMethod : uint8_t {
    Sah,              // binned surface area heuristic: the cheapest split plane per node
    Median,           // median cut: the longest side of the node's box, the items sorted by
                      // their lower bound on it, halved
    GoldsmithSalmon,  // items inserted one at a time (in a fixed shuffled order) beside the node
                      // where the tree's total surface area grows least, refitted bottom-up
};

struct BvhBuildOptions {
    // A node of at most this many items is a leaf; more only where no split pays (at most
    // four times this) or all centres coincide.
    uint32_t maxLeafItems = 1;
    // SAH cost of testing one box relative to testing one item.
    double traversalCost = 0.5;
    BvhMethod method = BvhMethod::Sah;
    // Threads for a large SAH build (0: one per core; ParallelFor.h): the tree is the same
    // with any number.
    int threads = 0;
};

// Builds a BVH over boxes (finite, non-empty; at least one), appending its nodes to `nodes`.
// `order` receives the leaf order: leaf slot ranges index it, offset by itemsOffset (slot =
// itemsOffset + position in order), and order[position] is the index into boxes. Returns the
// root node's index. A root that would be a leaf is one wide node with one slot. The tree is
// a function of the boxes and the options alone (deterministic). Median cut and
// Goldsmith-Salmon ignore traversalCost; Goldsmith-Salmon puts one item per leaf.
uint32_t buildWideBvh(std::span<const Bounds3> boxes, std::vector<uint32_t>& order,
                      uint32_t itemsOffset, const BvhBuildOptions& options,
                      std::vector<BvhNode>& nodes);

}  // namespace csg
