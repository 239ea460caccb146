// The contract of LocalSpans' hints (primitives/LocalSpans.h), checked against the whole list:
// shared by the tests of the primitives that take the hints (the torus, the polygon mesh).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "primitives/LocalSpans.h"
#include "primitives/base/Math.h"

namespace csg::testing {

// LocalSpans' hints (evalLeaf clips at `from`; closest() and any() on a leaf that is a whole
// object read only the first span left, and of it only where it begins, firstOnly): past
// `from`, the hinted list is the whole one, value for value, or with firstOnly a prefix of it
// that reaches at least to its first span whose part past `from` is longer than the margin (all
// of it when none is), whose end may come early but not so early that its part past `from` is
// no longer than the margin, nor when it begins no later than from + margin or follows a span
// that reaches past `from` (a ray that starts inside: closest() reads where it ends). The
// oracle is the same shape asked for the whole line. Counts the lists that differ from the
// whole one (placeholders) and the early ends.
template <class Shape>
void expectHintedPrefix(const Shape& shape, const Vec3& o, const Vec3& d, double from,
                        double margin, bool firstOnly, int& earlyEnds, int& placeholders) {
    LocalSpans whole, hinted;
    shape.spans(o, d, whole);
    hinted.firstOnly = firstOnly;
    hinted.from = from;
    hinted.margin = margin;
    shape.spans(o, d, hinted);
    // Both lists clipped at `from`, as evalLeaf does.
    const auto past = [&](const LocalSpans& s) {
        std::vector<std::pair<double, double>> out;
        for (int j = 0; j < s.count; ++j)
            if (s.entries[j].tOut >= from)
                out.push_back({std::max(s.entries[j].tIn, from), s.entries[j].tOut});
        return out;
    };
    const auto w = past(whole), h = past(hinted);
    ASSERT_LE(h.size(), w.size());
    for (size_t j = 0; j < h.size(); ++j) {
        ASSERT_EQ(h[j].first, w[j].first) << "span " << j;
        if (firstOnly && j + 1 == h.size() && h[j].second != w[j].second) {
            ASSERT_LT(h[j].second, w[j].second);
            ASSERT_GT(h[j].second - h[j].first, margin);
            ASSERT_GT(h[j].first, from + margin);  // not a span the ray starts inside,
            ASSERT_EQ(j, 0u);                      // nor one after a span past `from`
            ++earlyEnds;
        } else {
            ASSERT_EQ(h[j].second, w[j].second) << "span " << j;
        }
    }
    size_t needed = w.size();
    for (size_t j = 0; firstOnly && j < w.size(); ++j)
        if (w[j].second - w[j].first > margin) {
            needed = j + 1;
            break;
        }
    ASSERT_GE(h.size(), needed);
    for (int j = 0; j < std::min(whole.count, hinted.count); ++j)
        placeholders += whole.entries[j].tIn != hinted.entries[j].tIn ||
                        whole.entries[j].tOut != hinted.entries[j].tOut;
}

}  // namespace csg::testing
