// The lecture's two hierarchies besides the SAH (BinaryBvh.h): median cut and Goldsmith-Salmon
// insertion. Both leave the preorder binary tree WideBvh.cpp collapses.
#include <algorithm>
#include <limits>

#include "primitives/base/BinaryBvh.h"
#include "primitives/base/WideBvh.h"

namespace csg {
namespace {

struct MedianBuilder {
    std::span<const Bounds3> boxes;
    std::span<uint32_t> order;
    uint32_t maxLeafItems;
    std::vector<BinaryNode> nodes;

    uint32_t build(uint32_t lo, uint32_t hi) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        Bounds3 box;
        for (uint32_t i = lo; i < hi; ++i) box.extend(boxes[order[i]]);
        nodes[index].box = box;
        const uint32_t n = hi - lo;
        if (n <= maxLeafItems) {
            nodes[index].firstOrRight = lo;
            nodes[index].count = n;
            return index;
        }
        // The slab of greatest extent (the lecture's dmax - dmin), then the list by dmin.
        const Vec3 extent = box.extent();
        const int axis =
            extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
        const uint32_t mid = lo + n / 2;
        std::nth_element(order.begin() + lo, order.begin() + mid, order.begin() + hi,
                         [&](uint32_t a, uint32_t b) {
                             const double la = boxes[a].lo[axis], lb = boxes[b].lo[axis];
                             return la < lb || (la == lb && a < b);
                         });
        build(lo, mid);
        const uint32_t right = build(mid, hi);
        nodes[index].firstOrRight = right;
        nodes[index].count = 0;
        nodes[index].axis = axis;
        return index;
    }
};

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// The Goldsmith-Salmon tree while it grows: linked nodes, a leaf per item.
struct InsertionTree {
    struct Node {
        Bounds3 box;
        uint32_t parent = kNone;
        uint32_t child[2] = {kNone, kNone};
        uint32_t item = kNone;  // a leaf's item; kNone for an interior node
    };
    std::vector<Node> nodes;
    uint32_t root = kNone;

    // Inserts item (box b) beside the node where the cost grows least: making a new parent of
    // node s and the item costs the new parent's area plus, for every ancestor of s, the area
    // its box gains. The search follows one path, into the child whose box grows least (the
    // lecture's "few paths": one, which keeps a million insertions at O(n log n)).
    void insert(uint32_t item, const Bounds3& b) {
        const uint32_t leafIndex = static_cast<uint32_t>(nodes.size());
        nodes.push_back({b, kNone, {kNone, kNone}, item});
        if (root == kNone) {
            root = leafIndex;
            return;
        }
        uint32_t best = root, at = root;
        double bestCost = hull(nodes[root].box, b).halfArea(), inherited = 0.0;
        while (nodes[at].item == kNone) {
            inherited += hull(nodes[at].box, b).halfArea() - nodes[at].box.halfArea();
            uint32_t next = kNone;
            double nextGrowth = kInfinity;
            for (uint32_t c : nodes[at].child) {
                const double asSibling = hull(nodes[c].box, b).halfArea();
                if (asSibling + inherited < bestCost) {
                    bestCost = asSibling + inherited;
                    best = c;
                }
                const double growth = asSibling - nodes[c].box.halfArea();
                if (growth < nextGrowth) {
                    nextGrowth = growth;
                    next = c;
                }
            }
            // Below here every choice costs at least the item's own area more than inherited.
            if (inherited + b.halfArea() >= bestCost) break;
            at = next;
        }
        // A new interior node takes best's place, with best and the new leaf as children.
        const uint32_t parent = nodes[best].parent;
        const uint32_t joint = static_cast<uint32_t>(nodes.size());
        nodes.push_back({hull(nodes[best].box, b), parent, {best, leafIndex}, kNone});
        nodes[best].parent = joint;
        nodes[leafIndex].parent = joint;
        if (parent == kNone) {
            root = joint;
        } else {
            nodes[parent].child[nodes[parent].child[0] == best ? 0 : 1] = joint;
        }
        // Bottom-up refit of the boxes above.
        for (uint32_t up = parent; up != kNone; up = nodes[up].parent) nodes[up].box.extend(b);
    }

    // The tree in BinaryBvh.h's preorder layout; false when deeper than kBvhMaxDepth.
    bool linearize(std::span<uint32_t> order, std::vector<BinaryNode>& out) const {
        out.clear();
        out.reserve(nodes.size());
        struct Pending {
            uint32_t node;
            uint32_t parentSlot;  // where the right child's index goes, or kNone
            int depth;
        };
        std::vector<Pending> stack{{root, kNone, 0}};
        uint32_t placed = 0;
        while (!stack.empty()) {
            const Pending p = stack.back();
            stack.pop_back();
            if (p.depth >= kBvhMaxDepth) return false;
            const uint32_t index = static_cast<uint32_t>(out.size());
            if (p.parentSlot != kNone) out[p.parentSlot].firstOrRight = index;
            const Node& n = nodes[p.node];
            BinaryNode& b = out.emplace_back();
            b.box = n.box;
            if (n.item != kNone) {
                order[placed] = n.item;
                b.firstOrRight = placed++;
                b.count = 1;
                continue;
            }
            // Left is the child toward -axis, on the axis where the children's centres differ
            // most (what the 4-wide node's per-octant order needs).
            const Vec3 gap = nodes[n.child[1]].box.center() - nodes[n.child[0]].box.center();
            const Vec3 size = glm::abs(gap);
            const int axis =
                size.x >= size.y ? (size.x >= size.z ? 0 : 2) : (size.y >= size.z ? 1 : 2);
            const bool swap = gap[axis] < 0.0;
            b.axis = axis;
            b.count = 0;
            stack.push_back({n.child[swap ? 0 : 1], index, p.depth + 1});
            stack.push_back({n.child[swap ? 1 : 0], kNone, p.depth + 1});
        }
        return true;
    }
};

// SplitMix64: a fixed generator, so the insertion order is the same with any standard library.
uint64_t splitMix(uint64_t& state) {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

}  // namespace

std::vector<BinaryNode> buildMedianCut(std::span<const Bounds3> boxes, std::span<uint32_t> order,
                                       uint32_t maxLeafItems) {
    MedianBuilder builder{boxes, order, maxLeafItems, {}};
    builder.nodes.reserve(2 * boxes.size());
    builder.build(0, static_cast<uint32_t>(boxes.size()));
    return std::move(builder.nodes);
}

std::vector<BinaryNode> buildGoldsmithSalmon(std::span<const Bounds3> boxes,
                                             std::span<uint32_t> order, uint32_t maxLeafItems) {
    // Goldsmith and Salmon insert in random order: a scene listed row by row would otherwise
    // grow a lopsided tree.
    std::vector<uint32_t> sequence(boxes.size());
    for (uint32_t i = 0; i < sequence.size(); ++i) sequence[i] = i;
    uint64_t state = 0x5eed;
    for (size_t i = sequence.size(); i > 1; --i)
        std::swap(sequence[i - 1], sequence[splitMix(state) % i]);
    InsertionTree tree;
    tree.nodes.reserve(2 * boxes.size());
    for (uint32_t item : sequence) tree.insert(item, boxes[item]);
    std::vector<BinaryNode> out;
    if (tree.linearize(order, out)) return out;
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    return buildMedianCut(boxes, order, maxLeafItems);
}

}  // namespace csg
