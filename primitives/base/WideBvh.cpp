// The binned-SAH build and the BVH2 -> BVH4 collapse of primitives/base/WideBvh.h.
#include "primitives/base/WideBvh.h"

#include <algorithm>
#include <array>
#include <cassert>

#include "primitives/base/BinaryBvh.h"

namespace csg {
namespace {

constexpr int kBins = 16;
// Below this depth splits fall back to the median, so a walk's fixed stack (kBvhMaxDepth) can
// never overflow whatever the SAH would choose.
constexpr int kSahMaxDepth = kBvhMaxDepth - kBvhMedianLevels;

struct Builder {
    // An item's box beside its index, reordered in place as the tree is built: every pass over a
    // node's items then streams through memory, where gathering the boxes through an index
    // array jumped about the whole array at every level (bench/README.md, "Loading a large
    // mesh").
    struct Item {
        Bounds3 box;
        uint32_t index;
    };
    std::vector<Item> items;
    uint32_t maxLeafItems;
    double traversalCost;
    std::vector<BinaryNode> nodes;

    // The boxes of one axis's bins and their item counts.
    struct Bins {
        std::array<Bounds3, kBins> box;
        std::array<uint32_t, kBins> count{};
    };

    // Builds the node over items [lo, hi), whose box and centre bounds the caller has found.
    uint32_t build(uint32_t lo, uint32_t hi, int depth, const Bounds3& box,
                   const Bounds3& centroids) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        nodes[index].box = box;
        const uint32_t n = hi - lo;
        if (n <= maxLeafItems) return makeLeaf(index, lo, n);

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
            return makeLeaf(index, lo, n);  // splitting would not pay
        } else {
            // All centroids coincide (or no split pays): halve so depth stays logarithmic.
            mid = lo + n / 2;
        }
        if (mid == lo || mid == hi) mid = lo + n / 2;

        // The children's boxes and centre bounds: one more pass over the items costs less than
        // keeping each bin's centre bounds while binning.
        Bounds3 leftBox, leftCentroids, rightBox, rightCentroids;
        bound(lo, mid, leftBox, leftCentroids);
        bound(mid, hi, rightBox, rightCentroids);
        build(lo, mid, depth + 1, leftBox, leftCentroids);
        const uint32_t right = build(mid, hi, depth + 1, rightBox, rightCentroids);
        nodes[index].firstOrRight = right;
        nodes[index].count = 0;
        nodes[index].axis = bestAxis >= 0 ? bestAxis : 0;
        return index;
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
    const std::vector<BinaryNode>& binary;
    uint32_t itemsOffset;
    std::vector<BvhNode>& wide;

    uint32_t collapse(uint32_t interior) {
        uint32_t slots[4] = {interior + 1, binary[interior].firstOrRight, 0, 0};
        int count = 2;
        while (count < 4) {
            int open = -1;
            double openArea = -1.0;
            for (int k = 0; k < count; ++k) {
                const BinaryNode& b = binary[slots[k]];
                if (b.count == 0 && b.box.halfArea() > openArea) {
                    open = k;
                    openArea = b.box.halfArea();
                }
            }
            if (open < 0) break;  // only leaves left
            const uint32_t opened = slots[open];
            slots[open] = opened + 1;
            slots[count++] = binary[opened].firstOrRight;
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
            const BinaryNode& b = binary[slots[k]];
            const uint32_t target = b.count > 0 ? itemsOffset + b.firstOrRight : collapse(slots[k]);
            setSlot(wide[index], k, b.box, target, b.count);  // after collapse() grew `wide`
        }
        wide[index].slots = static_cast<uint8_t>(count);
        return index;
    }

    // Appends the slots under binary node b to `order` (two bits each), nearer first for a ray
    // of the given direction octant (bit a set: d[a] < 0): at each split the side toward which
    // the ray runs comes second, as the binary walk would visit them.
    void appendOrder(uint32_t b, unsigned octant, const uint32_t (&slots)[4], int count,
                     unsigned& order, int& placed) const {
        for (int k = 0; k < count; ++k) {
            if (slots[k] == b) {
                order |= unsigned(k) << (2 * placed++);
                return;
            }
        }
        const uint32_t left = b + 1, right = binary[b].firstOrRight;
        const bool leftFirst = (octant >> binary[b].axis & 1u) == 0;
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
    switch (options.method) {
        case BvhMethod::Sah: {
            Builder builder{{}, options.maxLeafItems, options.traversalCost, {}};
            builder.items.resize(boxes.size());
            for (uint32_t i = 0; i < boxes.size(); ++i) builder.items[i] = {boxes[i], i};
            Bounds3 box, centroids;
            builder.bound(0, static_cast<uint32_t>(boxes.size()), box, centroids);
            builder.nodes.reserve(2 * boxes.size());
            builder.build(0, static_cast<uint32_t>(boxes.size()), 0, box, centroids);
            for (uint32_t i = 0; i < order.size(); ++i) order[i] = builder.items[i].index;
            binary = std::move(builder.nodes);
            break;
        }
        case BvhMethod::Median:
            binary = buildMedianCut(boxes, order, options.maxLeafItems);
            break;
        case BvhMethod::GoldsmithSalmon:
            binary = buildGoldsmithSalmon(boxes, order, options.maxLeafItems);
            break;
    }
    // A root that is a leaf (items too few or all at one centre) is wrapped in one wide node.
    if (binary[0].count > 0) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        BvhNode& node = nodes.emplace_back();
        setSlot(node, 0, binary[0].box, itemsOffset, binary[0].count);
        node.slots = 1;
        return index;
    }
    Collapser collapser{binary, itemsOffset, nodes};
    return collapser.collapse(0);
}

}  // namespace csg
