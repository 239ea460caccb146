// Set operations on span lists against hand-derived results and a sampling oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "csg/SpanList.h"

namespace csg {
namespace {

using List = std::vector<Span>;

// Spans whose ends carry leaf ids `leaf` (in) and `leaf` (out) and surface face 0.
List spans(std::initializer_list<std::pair<double, double>> ranges, uint32_t leaf) {
    List out;
    for (auto [a, b] : ranges) out.push_back({{a, leaf, 0, false}, {b, leaf, 0, false}});
    return out;
}

List merge(SetOp op, const List& a, const List& b, double originScale = 0.0) {
    List out(a.size() + b.size());
    out.resize(mergeSpans(op, a.data(), a.size(), b.data(), b.size(), out.data(), originScale));
    return out;
}

void expectRanges(const List& got, std::initializer_list<std::pair<double, double>> want) {
    ASSERT_EQ(got.size(), want.size());
    size_t i = 0;
    for (auto [a, b] : want) {
        EXPECT_DOUBLE_EQ(got[i].in.t, a) << "span " << i;
        EXPECT_DOUBLE_EQ(got[i].out.t, b) << "span " << i;
        ++i;
    }
}

TEST(SpanList, UnionOverlappingAndDisjoint) {
    const List a = spans({{0, 2}, {5, 6}}, 1), b = spans({{1, 3}, {7, 8}}, 2);
    const List u = merge(SetOp::Union, a, b);
    expectRanges(u, {{0, 3}, {5, 6}, {7, 8}});
    EXPECT_EQ(u[0].in.leaf, 1u);
    EXPECT_EQ(u[0].out.leaf, 2u);
}

TEST(SpanList, IntersectionKeepsOverlapOnly) {
    const List i =
        merge(SetOp::Intersection, spans({{0, 2}, {5, 9}}, 1), spans({{1, 6}, {8, 10}}, 2));
    expectRanges(i, {{1, 2}, {5, 6}, {8, 9}});
    EXPECT_EQ(i[0].in.leaf, 2u);
    EXPECT_EQ(i[0].out.leaf, 1u);
}

TEST(SpanList, DifferenceFlipsTheCutsHits) {
    const List d = merge(SetOp::Difference, spans({{0, 10}}, 1), spans({{2, 3}, {9, 12}}, 2));
    expectRanges(d, {{0, 2}, {3, 9}});
    EXPECT_FALSE(d[0].in.flipped);
    EXPECT_TRUE(d[0].out.flipped);  // the cut's entry face bounds the result from inside
    EXPECT_EQ(d[0].out.leaf, 2u);
    EXPECT_TRUE(d[1].in.flipped);
    EXPECT_TRUE(d[1].out.flipped);
}

TEST(SpanList, IdentitiesOnRandomLists) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-100, 100);
    for (int trial = 0; trial < 1000; ++trial) {
        std::vector<double> ends(2 * (1 + trial % 6));
        for (double& e : ends) e = u(rng);
        std::sort(ends.begin(), ends.end());
        List a;
        for (size_t i = 0; i < ends.size(); i += 2)
            a.push_back({{ends[i], 3, 0, false}, {ends[i + 1], 3, 1, false}});
        // Regularize a first (random ends may be closer than the tolerance).
        a = merge(SetOp::Union, a, {});
        const List uni = merge(SetOp::Union, a, a);
        const List inter = merge(SetOp::Intersection, a, a);
        ASSERT_EQ(uni.size(), a.size());
        ASSERT_EQ(inter.size(), a.size());
        for (size_t i = 0; i < a.size(); ++i) {
            EXPECT_EQ(uni[i].in.t, a[i].in.t);
            EXPECT_EQ(uni[i].out.t, a[i].out.t);
            EXPECT_EQ(inter[i].in.face, a[i].in.face);
            EXPECT_EQ(inter[i].out.face, a[i].out.face);
            EXPECT_FALSE(inter[i].out.flipped);
        }
        EXPECT_TRUE(merge(SetOp::Difference, a, a).empty());
    }
}

TEST(SpanList, FaceSharingSpansFuseEvenWhenEndsDifferByRounding) {
    // Two boxes [0,1] and [1,2] along a ray from far away: the shared face's t comes out of
    // two different frames and may differ in the last bits.
    const double t = 1e6 + 1.0;
    const List a = spans({{1e6, t}}, 1);
    const List b = spans({{std::nextafter(t, 0.0), 1e6 + 2}}, 2);
    const List c = spans({{std::nextafter(t, 1e7), 1e6 + 2}}, 2);
    for (const List& right : {b, c}) {
        const List u = merge(SetOp::Union, a, right, 1e6);
        ASSERT_EQ(u.size(), 1u);
        EXPECT_EQ(u[0].in.leaf, 1u);
        EXPECT_EQ(u[0].out.leaf, 2u);
    }
}

TEST(SpanList, CoincidentFaceInDifferenceLeavesNoSliver) {
    // Box [0,2] minus a box [1,2] that shares the far face, ends off by an ulp either way.
    for (double far : {2.0, std::nextafter(2.0, 0.0), std::nextafter(2.0, 3.0)}) {
        const List d = merge(SetOp::Difference, spans({{0, 2}}, 1), spans({{1, far}}, 2));
        expectRanges(d, {{0, 1}});
        EXPECT_TRUE(d[0].out.flipped);
    }
}

TEST(SpanList, TieBreakPrefersSurfacesThenTheLeftHitOrAUnionsLowerLeaf) {
    List a = spans({{1, 4}}, 1);
    List b = spans({{1, 4}}, 2);
    const List u = merge(SetOp::Union, a, b);
    EXPECT_EQ(u[0].in.leaf, 1u);
    EXPECT_EQ(u[0].out.leaf, 1u);
    // A union names the lower leaf at coincident surfaces in either order (a BVH merges a
    // union's children in an order that changes from ray to ray), entering or leaving.
    const List swapped = merge(SetOp::Union, b, a);
    EXPECT_EQ(swapped[0].in.leaf, 1u);
    EXPECT_EQ(swapped[0].out.leaf, 1u);
    const List tail = merge(SetOp::Union, spans({{2, 4}}, 7), spans({{0, 4}}, 3));
    expectRanges(tail, {{0, 4}});
    EXPECT_EQ(tail[0].out.leaf, 3u);
    // An intersection and a difference keep the left operand's: their order is the tree's.
    EXPECT_EQ(merge(SetOp::Intersection, b, a)[0].in.leaf, 2u);
    // A clip end (a narrowed range) never wins against a surface at the same t.
    b[0].in.face = kClipFace;
    a[0].out.face = kClipFace;
    const List i = merge(SetOp::Intersection, a, b);
    ASSERT_EQ(i.size(), 1u);
    EXPECT_TRUE(i[0].in.isSurface());
    EXPECT_EQ(i[0].in.leaf, 1u);
    EXPECT_TRUE(i[0].out.isSurface());
    EXPECT_EQ(i[0].out.leaf, 2u);
    // Of two clip ends at one t (both operands narrowed there), the left operand's.
    List c = spans({{1, 4}}, 1), e = spans({{0, 4}}, 2);
    c[0].out.face = kClipFace;
    e[0].out.face = kClipFace;
    EXPECT_EQ(merge(SetOp::Intersection, c, e)[0].out.leaf, 1u);
    EXPECT_EQ(merge(SetOp::Intersection, e, c)[0].out.leaf, 2u);
}

TEST(SpanList, SpansToInfinityAreNotSlivers) {
    const double inf = std::numeric_limits<double>::infinity();
    const List u = merge(SetOp::Union, spans({{1, inf}}, 1), spans({{-inf, -1}}, 2));
    expectRanges(u, {{-inf, -1}, {1, inf}});
}

TEST(SpanList, SliversShorterThanTheToleranceAreDropped) {
    const List i = merge(SetOp::Intersection, spans({{0, 1}}, 1), spans({{1 - 1e-12, 3}}, 2));
    EXPECT_TRUE(i.empty());
    const List kept = merge(SetOp::Intersection, spans({{0, 1}}, 1), spans({{1 - 1e-6, 3}}, 2));
    EXPECT_EQ(kept.size(), 1u);
}

// Membership oracle: is t inside one of the spans (open interior)?
bool member(const List& l, double t) {
    for (const Span& s : l)
        if (t > s.in.t && t < s.out.t) return true;
    return false;
}

TEST(SpanList, AllOperationsAgreeWithPointSampling) {
    std::mt19937_64 rng(11);
    std::uniform_int_distribution<int> grid(0, 40);  // integer ends: exact ties are common
    auto randomList = [&] {
        std::vector<double> ends;
        const int n = 2 * std::uniform_int_distribution<int>(0, 5)(rng);
        for (int i = 0; i < n; ++i) ends.push_back(grid(rng));
        std::sort(ends.begin(), ends.end());
        List l;
        for (size_t i = 0; i + 1 < ends.size(); i += 2)
            if (ends[i] < ends[i + 1] && (l.empty() || ends[i] > l.back().out.t))
                l.push_back({{ends[i], 0, 0, false}, {ends[i + 1], 0, 0, false}});
        return l;
    };
    for (int trial = 0; trial < 5000; ++trial) {
        const List a = randomList(), b = randomList();
        for (SetOp op : {SetOp::Union, SetOp::Intersection, SetOp::Difference}) {
            const List r = merge(op, a, b);
            for (size_t i = 1; i < r.size(); ++i) ASSERT_LT(r[i - 1].out.t, r[i].in.t);
            for (double t = -0.5; t < 41; t += 0.5) {
                if (t == std::floor(t)) continue;  // ends sit on integers
                const bool inA = member(a, t), inB = member(b, t);
                const bool want = op == SetOp::Union          ? inA || inB
                                  : op == SetOp::Intersection ? inA && inB
                                                              : inA && !inB;
                ASSERT_EQ(member(r, t), want) << "op " << int(op) << " t " << t;
            }
        }
    }
}

// Two single spans take a path of their own through mergeSolidSpans (a part's box and sphere,
// its bores); the same two with a span far past both appended to the right operand take the
// event loop, where that span adds nothing before itself: the loop is the oracle, hit for hit.
// Ends come from a few values, so that every kind of tie occurs, some moved off a value within
// the coincidence slack, so that slivers are dropped and gaps closed; faces are surfaces or
// clip ends, and leaves and flips vary, so that every tie-break decides. (The tie-breaks
// themselves, tiedEnd and tiedUnionEnd, are the loop's too: the test above holds them by hand.)
TEST(SpanList, SingleSpanMergesAgreeWithTheEventLoop) {
    std::mt19937_64 rng(4242);
    std::uniform_int_distribution<int> value(0, 3), leaf(1, 3), coin(0, 3);
    constexpr double kOriginScale = 1.0;
    const auto end = [&](double t) {
        Hit h{t, uint32_t(leaf(rng)), coin(rng) == 0 ? kClipFace : uint16_t(coin(rng)),
              coin(rng) == 0};
        if (coin(rng) == 0)  // within the slack of the value (1e-9 * (1 + 3) at most)
            h.t += (coin(rng) - 1.5) * 1e-9;
        return h;
    };
    const auto randomSpan = [&] {
        int lo = value(rng), hi = value(rng);
        while (hi == lo) hi = value(rng);
        return Span{end(std::min(lo, hi)), end(std::max(lo, hi))};
    };
    const Span far{{100.0, 9, 0, false}, {101.0, 9, 0, false}};
    const auto same = [](const Hit& x, const Hit& y) {
        return x.t == y.t && x.leaf == y.leaf && x.face == y.face && x.flipped == y.flipped &&
               x.sheet == y.sheet;
    };
    int ties = 0, results[4] = {};
    for (int trial = 0; trial < 100000; ++trial) {
        const Span a = randomSpan(), b = randomSpan();
        ties += a.in.t == b.in.t || a.in.t == b.out.t || a.out.t == b.in.t || a.out.t == b.out.t;
        for (SetOp op : {SetOp::Union, SetOp::Intersection, SetOp::Difference}) {
            Span single[2], looped[3];
            const size_t n = mergeSolidSpans(op, &a, 1, &b, 1, single, kOriginScale);
            const Span padded[2] = {b, far};
            size_t m = mergeSolidSpans(op, &a, 1, padded, 2, looped, kOriginScale);
            if (op == SetOp::Union) {
                ASSERT_GE(m, 1u);
                ASSERT_EQ(looped[m - 1].in.t, far.in.t);
                --m;
            }
            ASSERT_EQ(n, m) << "trial " << trial << " op " << int(op);
            for (size_t i = 0; i < n; ++i) {
                ASSERT_TRUE(same(single[i].in, looped[i].in)) << "trial " << trial;
                ASSERT_TRUE(same(single[i].out, looped[i].out)) << "trial " << trial;
            }
            ++results[n];
        }
    }
    // Every outcome occurred, and ties often: the paths were compared where they could differ.
    EXPECT_GT(ties, 10000);
    EXPECT_GT(results[0], 1000);
    EXPECT_GT(results[1], 1000);
    EXPECT_GT(results[2], 1000);
}

}  // namespace
}  // namespace csg
