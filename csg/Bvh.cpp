#include "csg/Bvh.h"

#include <algorithm>
#include <array>

namespace csg {
namespace {

constexpr int kBins = 16;
// One child per leaf (more only where no split pays): the leaf's box is then the child's own,
// so the ray loop does not test the child's bounds again (CompiledNode::boundsImplied); two
// per leaf cost 1.8 % more instructions on bench/scenes/csg_grid.
constexpr uint32_t kMaxLeafItems = 1;
// SAH cost of testing one child's bounds relative to evaluating one child.
constexpr double kTraversalCost = 0.5;
// Below this depth splits fall back to the median, so traversal's fixed stack (kBvhMaxDepth)
// can never overflow whatever the SAH would choose.
constexpr int kSahMaxDepth = kBvhMaxDepth - 24;

struct Builder {
    std::span<uint32_t> items;
    const std::vector<CompiledNode>& itemNodes;
    uint32_t itemsOffset;
    std::vector<BvhNode>& nodes;

    uint32_t build(uint32_t lo, uint32_t hi, int depth) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        Bounds3 box, centroids;
        for (uint32_t i = lo; i < hi; ++i) {
            box.extend(itemNodes[items[i]].bounds);
            centroids.extend(itemNodes[items[i]].bounds.center());
        }
        nodes[index].box = box;
        const uint32_t n = hi - lo;
        if (n <= kMaxLeafItems) return makeLeaf(index, lo, n);

        // Pick the split plane of least SAH cost over binned centroids on all three axes.
        int bestAxis = -1, bestBin = 0;
        double bestCost = static_cast<double>(n);  // cost of a leaf, relative to box area
        for (int axis = 0; axis < 3 && depth < kSahMaxDepth; ++axis) {
            const double lo0 = centroids.lo[axis], width = centroids.hi[axis] - lo0;
            if (!(width > 0.0)) continue;
            std::array<Bounds3, kBins> binBox;
            std::array<uint32_t, kBins> binCount{};
            for (uint32_t i = lo; i < hi; ++i) {
                const Bounds3& b = itemNodes[items[i]].bounds;
                const int bin = binOf(b.center()[axis], lo0, width);
                binBox[bin].extend(b);
                ++binCount[bin];
            }
            // Sweep from the right to get each suffix's area and count, then from the left.
            std::array<double, kBins> rightArea{};
            std::array<uint32_t, kBins> rightCount{};
            Bounds3 acc;
            uint32_t cnt = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.extend(binBox[b]);
                cnt += binCount[b];
                rightArea[b] = acc.halfArea();
                rightCount[b] = cnt;
            }
            acc = Bounds3{};
            cnt = 0;
            const double invArea = 1.0 / std::max(box.halfArea(), 1e-300);
            for (int b = 0; b < kBins - 1; ++b) {
                acc.extend(binBox[b]);
                cnt += binCount[b];
                if (cnt == 0 || rightCount[b + 1] == 0) continue;
                const double cost =
                    kTraversalCost +
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
            const double lo0 = centroids.lo[bestAxis];
            const double width = centroids.hi[bestAxis] - lo0;
            const auto split =
                std::partition(items.begin() + lo, items.begin() + hi, [&](uint32_t it) {
                    return binOf(itemNodes[it].bounds.center()[bestAxis], lo0, width) <= bestBin;
                });
            mid = static_cast<uint32_t>(split - items.begin());
        } else if (n <= 4 * kMaxLeafItems) {
            return makeLeaf(index, lo, n);  // splitting would not pay
        } else {
            // All centroids coincide (or no split pays): halve so depth stays logarithmic.
            mid = lo + n / 2;
        }
        if (mid == lo || mid == hi) mid = lo + n / 2;
        const int axis = bestAxis >= 0 ? bestAxis : 0;

        build(lo, mid, depth + 1);
        const uint32_t right = build(mid, hi, depth + 1);
        nodes[index].firstOrRight = right;
        nodes[index].count = 0;
        nodes[index].axis = static_cast<uint8_t>(axis);
        return index;
    }

    static int binOf(double c, double lo0, double width) {
        const int bin = static_cast<int>(kBins * ((c - lo0) / width));
        return std::clamp(bin, 0, kBins - 1);
    }

    uint32_t makeLeaf(uint32_t index, uint32_t lo, uint32_t n) {
        nodes[index].firstOrRight = itemsOffset + lo;
        nodes[index].count = static_cast<uint16_t>(n);
        return index;
    }
};

}  // namespace

uint32_t buildBvh(std::span<uint32_t> items, const std::vector<CompiledNode>& itemNodes,
                  uint32_t itemsOffset, std::vector<BvhNode>& nodes) {
    Builder builder{items, itemNodes, itemsOffset, nodes};
    return builder.build(0, static_cast<uint32_t>(items.size()), 0);
}

}  // namespace csg
