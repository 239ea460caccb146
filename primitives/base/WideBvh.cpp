// The binned-SAH build and the BVH2 -> BVH4 collapse of primitives/base/WideBvh.h.
#include "primitives/base/WideBvh.h"

#include <algorithm>
#include <array>
#include <cassert>

#include "primitives/base/BinaryBvh.h"
#include "primitives/base/ParallelFor.h"

namespace csg {
namespace {

constexpr int kBins = 16;
// Below this depth splits fall back to the median, so a walk's fixed stack (kBvhMaxDepth) can
// never overflow whatever the SAH would choose.
constexpr int kSahMaxDepth = kBvhMaxDepth - kBvhMedianLevels;
// The SAH build of this many items or more runs on several threads (BvhBuildOptions::threads):
// below it, starting the threads would cost more than they save. Its parts hold at most
// 1 / kTasksPerThread of a thread's share of the items (but not fewer than half this many),
// so that parts of unequal size still share out evenly.
constexpr uint32_t kParallelBuildItems = 1u << 15;
constexpr uint32_t kTasksPerThread = 4;

struct Builder {
    // An item's box beside its index, reordered in place as the tree is built: every pass over a
    // node's items then streams through memory, where gathering the boxes through an index
    // array jumped about the whole array at every level (bench/README.md, "Loading a large
    // mesh").
    struct Item {
        Bounds3 box;
        uint32_t index;
    };
    // Shared by the builders of one tree, each of which reorders only its own range.
    std::span<Item> items;
    uint32_t maxLeafItems;
    double traversalCost;
    std::vector<BinaryNode> nodes;
    // A builder of a tree's top only (buildInParts) leaves each node of at most partItems items
    // a placeholder, noted in parts for a builder of its own; 0: it builds the whole tree.
    uint32_t partItems = 0;
    struct Part {
        uint32_t node;  // the placeholder
        uint32_t lo, hi;
        int depth;
        Bounds3 box, centroids;
    };
    std::vector<Part> parts{};

    // The boxes of one axis's bins and their item counts.
    struct Bins {
        std::array<Bounds3, kBins> box;
        std::array<uint32_t, kBins> count{};
    };

    // How a node's items [lo, hi) divide: [lo, mid) to the left, split on axis, with each
    // side's box and centre bounds.
    struct Split {
        uint32_t mid = 0;
        int axis = 0;
        Bounds3 leftBox, leftCentroids, rightBox, rightCentroids;
    };

    // Builds the node over items [lo, hi), whose box and centre bounds the caller has found.
    uint32_t build(uint32_t lo, uint32_t hi, int depth, const Bounds3& box,
                   const Bounds3& centroids) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        nodes[index].box = box;
        if (hi - lo <= partItems) {
            parts.push_back({index, lo, hi, depth, box, centroids});
            return index;
        }
        Split s;
        if (!split(lo, hi, depth, box, centroids, s)) return makeLeaf(index, lo, hi - lo);
        build(lo, s.mid, depth + 1, s.leftBox, s.leftCentroids);
        const uint32_t right = build(s.mid, hi, depth + 1, s.rightBox, s.rightCentroids);
        nodes[index].firstOrRight = right;
        nodes[index].count = 0;
        nodes[index].axis = s.axis;
        return index;
    }

    // Reorders items [lo, hi) into the node's two sides and says where they divide; false for a
    // node that stays a leaf.
    bool split(uint32_t lo, uint32_t hi, int depth, const Bounds3& box, const Bounds3& centroids,
               Split& out) {
        const uint32_t n = hi - lo;
        if (n <= maxLeafItems) return false;

        // Bin the centres on every axis with a spread, in one pass over the items.
        std::array<Bins, 3> bins;
        const Vec3 width = centroids.extent();
        bool binned[3] = {};
        for (int axis = 0; axis < 3 && depth < kSahMaxDepth; ++axis)
            binned[axis] = width[axis] > 0.0;
        if (binned[0] || binned[1] || binned[2]) {
            for (uint32_t i = lo; i < hi; ++i) {
                const Bounds3& b = items[i].box;
                const Vec3 c = b.center();
                for (int axis = 0; axis < 3; ++axis) {
                    if (!binned[axis]) continue;
                    const int bin = binOf(c[axis], centroids.lo[axis], width[axis]);
                    bins[axis].box[bin].extend(b);
                    ++bins[axis].count[bin];
                }
            }
        }

        // Pick the split plane of least SAH cost over the binned centroids.
        int bestAxis = -1, bestBin = 0;
        double bestCost = static_cast<double>(n);  // cost of a leaf, relative to box area
        const double invArea = 1.0 / std::max(box.halfArea(), 1e-300);
        for (int axis = 0; axis < 3; ++axis) {
            if (!binned[axis]) continue;
            const Bins& at = bins[axis];
            // Sweep from the right to get each suffix's area and count, then from the left.
            std::array<double, kBins> rightArea{};
            std::array<uint32_t, kBins> rightCount{};
            Bounds3 acc;
            uint32_t cnt = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.extend(at.box[b]);
                cnt += at.count[b];
                rightArea[b] = acc.halfArea();
                rightCount[b] = cnt;
            }
            acc = Bounds3{};
            cnt = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.extend(at.box[b]);
                cnt += at.count[b];
                if (cnt == 0 || rightCount[b + 1] == 0) continue;
                const double cost =
                    traversalCost +
                    (acc.halfArea() * cnt + rightArea[b + 1] * rightCount[b + 1]) * invArea;
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = b;
                }
            }
        }

        uint32_t mid;
        if (bestAxis >= 0) {
            const double lo0 = centroids.lo[bestAxis], w = width[bestAxis];
            const auto split =
                std::partition(items.begin() + lo, items.begin() + hi, [&](const Item& it) {
                    return binOf(it.box.center()[bestAxis], lo0, w) <= bestBin;
                });
            mid = static_cast<uint32_t>(split - items.begin());
        } else if (n <= 4 * maxLeafItems) {
            return false;  // splitting would not pay
        } else {
            // All centroids coincide (or no split pays): halve so depth stays logarithmic.
            mid = lo + n / 2;
        }
        if (mid == lo || mid == hi) mid = lo + n / 2;

        // The children's boxes and centre bounds: one more pass over the items costs less than
        // keeping each bin's centre bounds while binning.
        out = {};
        out.mid = mid;
        out.axis = bestAxis >= 0 ? bestAxis : 0;
        bound(lo, mid, out.leftBox, out.leftCentroids);
        bound(mid, hi, out.rightBox, out.rightCentroids);
        return true;
    }

    // The box of items [lo, hi) and the bounds of their centres.
    void bound(uint32_t lo, uint32_t hi, Bounds3& box, Bounds3& centroids) const {
        for (uint32_t i = lo; i < hi; ++i) {
            box.extend(items[i].box);
            centroids.extend(items[i].box.center());
        }
    }

    static int binOf(double c, double lo0, double width) {
        const int bin = static_cast<int>(kBins * ((c - lo0) / width));
        return std::clamp(bin, 0, kBins - 1);
    }

    uint32_t makeLeaf(uint32_t index, uint32_t lo, uint32_t n) {
        nodes[index].firstOrRight = lo;
        nodes[index].count = n;
        return index;
    }
};

// A part's placeholder in partAt (BinaryTree): none.
constexpr uint32_t kNoPart = ~0u;

// The SAH tree on several threads, node for node the one Builder::build makes alone: `top`
// (partItems set) builds the top on this thread, splitting it as build() would; each part it
// leaves is built at once by a Builder of its own over its own range of the shared items. The
// parts stay in arrays of their own (returned in the order of top.parts), which the collapse
// steps into from the top's placeholders (BinaryTree): copying them into one array cost up to a
// fifth of the build, most of it in fresh pages.
std::vector<std::vector<BinaryNode>> buildInParts(Builder& top, uint32_t count, const Bounds3& box,
                                                  const Bounds3& centroids, int threads) {
    top.build(0, count, 0, box, centroids);
    std::vector<std::vector<BinaryNode>> parts(top.parts.size());
    parallelFor(parts.size(), threads, [&](int, uint64_t k) {
        const Builder::Part& p = top.parts[k];
        Builder part{top.items, top.maxLeafItems, top.traversalCost, {}};
        part.nodes.reserve(2 * size_t(p.hi - p.lo));
        part.build(p.lo, p.hi, p.depth, p.box, p.centroids);
        parts[k] = std::move(part.nodes);
    });
    return parts;
}

// A binary tree in preorder (BinaryBvh.h), in one array, or in the top's array and its parts'
// (buildInParts), each part's interior nodes naming their right child by its place in the
// part. A node is reached through a Ref: the node and the array it lies in.
struct BinaryTree {
    std::span<const BinaryNode> top;
    std::span<const uint32_t> partAt;  // empty: no parts
    std::span<const std::vector<BinaryNode>> parts;

    struct Ref {
        const BinaryNode* node;
        const BinaryNode* array;
        bool operator==(const Ref& other) const { return node == other.node; }
    };

    // The node at `index` of `array`, or, for a placeholder of the top's, its part's root.
    Ref at(const BinaryNode* array, uint32_t index) const {
        if (array == top.data() && !partAt.empty() && partAt[index] != kNoPart) {
            const BinaryNode* part = parts[partAt[index]].data();
            return {part, part};
        }
        return {array + index, array};
    }
    Ref root() const { return at(top.data(), 0); }
    Ref left(Ref r) const { return at(r.array, static_cast<uint32_t>(r.node - r.array) + 1); }
    Ref right(Ref r) const { return at(r.array, r.node->firstOrRight); }
};

// Slot k of a wide node: its box, and the node or the leaf's first child it leads to.
void setSlot(BvhNode& node, int k, const Bounds3& box, uint32_t target, uint32_t leafCount) {
    node.boxes.set(k, box);
    node.slot[k] = target;
    node.leafCount[k] = static_cast<uint8_t>(leafCount);
}

// Collapses the binary tree into 4-wide nodes: a wide node takes a binary node's two children
// and keeps opening the interior one of largest area among its slots (its two children take
// its place) until it has four, so the slots a ray is most likely to enter are the ones the
// wide node resolves at once (the usual BVH2 -> BVH4 collapse, as in Embree).
struct Collapser {
    using Ref = BinaryTree::Ref;
    const BinaryTree& binary;
    uint32_t itemsOffset;
    std::vector<BvhNode>& wide;

    uint32_t collapse(Ref interior) {
        Ref slots[4] = {binary.left(interior), binary.right(interior), {}, {}};
        int count = 2;
        while (count < 4) {
            int open = -1;
            double openArea = -1.0;
            for (int k = 0; k < count; ++k) {
                const BinaryNode& b = *slots[k].node;
                if (b.count == 0 && b.box.halfArea() > openArea) {
                    open = k;
                    openArea = b.box.halfArea();
                }
            }
            if (open < 0) break;  // only leaves left
            const Ref opened = slots[open];
            slots[open] = binary.left(opened);
            slots[count++] = binary.right(opened);
        }

        const uint32_t index = static_cast<uint32_t>(wide.size());
        wide.emplace_back();
        for (unsigned octant = 0; octant < 8; ++octant) {
            unsigned order = 0;
            int placed = 0;
            appendOrder(interior, octant, slots, count, order, placed);
            wide[index].order[octant] = static_cast<uint8_t>(order);
        }
        for (int k = 0; k < count; ++k) {
            const BinaryNode& b = *slots[k].node;
            const uint32_t target = b.count > 0 ? itemsOffset + b.firstOrRight : collapse(slots[k]);
            setSlot(wide[index], k, b.box, target, b.count);  // after collapse() grew `wide`
        }
        wide[index].slots = static_cast<uint8_t>(count);
        return index;
    }

    // Appends the slots under binary node b to `order` (two bits each), nearer first for a ray
    // of the given direction octant (bit a set: d[a] < 0): at each split the side toward which
    // the ray runs comes second, as the binary walk would visit them.
    void appendOrder(Ref b, unsigned octant, const Ref (&slots)[4], int count, unsigned& order,
                     int& placed) const {
        for (int k = 0; k < count; ++k) {
            if (slots[k] == b) {
                order |= unsigned(k) << (2 * placed++);
                return;
            }
        }
        const Ref left = binary.left(b), right = binary.right(b);
        const bool leftFirst = (octant >> b.node->axis & 1u) == 0;
        appendOrder(leftFirst ? left : right, octant, slots, count, order, placed);
        appendOrder(leftFirst ? right : left, octant, slots, count, order, placed);
    }
};

}  // namespace

uint32_t buildWideBvh(std::span<const Bounds3> boxes, std::vector<uint32_t>& order,
                      uint32_t itemsOffset, const BvhBuildOptions& options,
                      std::vector<BvhNode>& nodes) {
    assert(!boxes.empty() && options.maxLeafItems >= 1 && 4 * options.maxLeafItems <= 255);
    order.resize(boxes.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::vector<BinaryNode> binary;
    std::vector<uint32_t> partAt;
    std::vector<std::vector<BinaryNode>> parts;
    switch (options.method) {
        case BvhMethod::Sah: {
            std::vector<Builder::Item> items(boxes.size());
            for (uint32_t i = 0; i < boxes.size(); ++i) items[i] = {boxes[i], i};
            Builder builder{items, options.maxLeafItems, options.traversalCost, {}};
            const uint32_t count = static_cast<uint32_t>(boxes.size());
            Bounds3 box, centroids;
            builder.bound(0, count, box, centroids);
            const int threads = resolveThreads(options.threads);
            if (threads > 1 && count >= kParallelBuildItems) {
                builder.partItems =
                    std::max(kParallelBuildItems / 2, count / (kTasksPerThread * threads));
                parts = buildInParts(builder, count, box, centroids, threads);
                partAt.assign(builder.nodes.size(), kNoPart);
                for (uint32_t k = 0; k < builder.parts.size(); ++k)
                    partAt[builder.parts[k].node] = k;
            } else {
                builder.nodes.reserve(2 * boxes.size());
                builder.build(0, count, 0, box, centroids);
            }
            binary = std::move(builder.nodes);
            for (uint32_t i = 0; i < order.size(); ++i) order[i] = items[i].index;
            break;
        }
        case BvhMethod::Median:
            binary = buildMedianCut(boxes, order, options.maxLeafItems);
            break;
        case BvhMethod::GoldsmithSalmon:
            binary = buildGoldsmithSalmon(boxes, order, options.maxLeafItems);
            break;
    }
    const BinaryTree tree{binary, partAt, parts};
    // A root that is a leaf (items too few or all at one centre) is wrapped in one wide node.
    const BinaryNode& root = *tree.root().node;
    if (root.count > 0) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        BvhNode& node = nodes.emplace_back();
        setSlot(node, 0, root.box, itemsOffset, root.count);
        node.slots = 1;
        return index;
    }
    Collapser collapser{tree, itemsOffset, nodes};
    return collapser.collapse(tree.root());
}

}  // namespace csg
