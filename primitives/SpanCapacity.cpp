#include "primitives/SpanCapacity.h"

#include <algorithm>

namespace csg {

void addWithinCapacity(const std::vector<LocalSpans::Entry>& spans, LocalSpans& out) {
    const size_t n = spans.size();
    if (n <= size_t(LocalSpans::kCapacity)) {
        for (const LocalSpans::Entry& e : spans) out.add(e.tIn, e.faceIn, e.tOut, e.faceOut);
        return;
    }
    thread_local std::vector<double> gaps, sorted;
    gaps.clear();
    for (size_t i = 0; i + 1 < n; ++i) gaps.push_back(spans[i + 1].tIn - spans[i].tOut);
    size_t toClose = n - LocalSpans::kCapacity;
    sorted.assign(gaps.begin(), gaps.end());
    std::nth_element(sorted.begin(), sorted.begin() + long(toClose - 1), sorted.end());
    const double threshold = sorted[toClose - 1];
    const size_t below =
        size_t(std::count_if(gaps.begin(), gaps.end(), [&](double g) { return g < threshold; }));
    size_t atThreshold = toClose - below;  // ties at the threshold are closed first in t
    size_t i = 0;
    while (i < n) {
        const size_t first = i;
        while (i + 1 < n && toClose > 0 &&
               (gaps[i] < threshold || (gaps[i] == threshold && atThreshold > 0))) {
            if (!(gaps[i] < threshold)) --atThreshold;
            --toClose;
            ++i;
        }
        out.add(spans[first].tIn, spans[first].faceIn, spans[i].tOut, spans[i].faceOut);
        ++i;
    }
}

}  // namespace csg
