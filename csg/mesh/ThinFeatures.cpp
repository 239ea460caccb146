#include "csg/mesh/ThinFeatures.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

// Casts after the first: each round's planes bring new lines, which can only reveal thin
// features crossing those planes; two rounds more settle every part we have measured.
constexpr int kThinRounds = 3;

// Per axis, the greedy stabbing points of the intervals at least minWidth wide; returns false
// (points incomplete) as soon as more than maxCount would be needed.
bool stab(const std::vector<ThinInterval>& byUpperEnd, double minWidth, int maxCount,
          std::vector<double>& points) {
    points.clear();
    // The last point lies below every later interval's upper end, so it stabs a later interval
    // exactly when it lies above that interval's lower end.
    double last = -std::numeric_limits<double>::infinity();
    for (const ThinInterval& i : byUpperEnd) {
        if (i.hi - i.lo < minWidth || last > i.lo) continue;
        if (int(points.size()) == maxCount) return false;
        last = 0.5 * (i.lo + i.hi);
        points.push_back(last);
    }
    return true;
}

}  // namespace

GridSpec withThinPlanes(const GridSpec& spec, const HermiteGrid& grid, double minWidth,
                        int maxPerAxis, uint64_t* added, bool* capped) {
    std::array<std::vector<double>, 3> coords = spec.coords;
    for (size_t a = 0; a < 3; ++a) {
        std::vector<ThinInterval> thin = grid.thinIntervals()[a];
        std::sort(thin.begin(), thin.end(),
                  [](const ThinInterval& x, const ThinInterval& y) { return x.hi < y.hi; });
        // Over the allowance: the widest features first (a fused gap reaches the further into
        // the part the wider it is), by doubling the narrowest width resolved until it fits.
        std::vector<double> points;
        double width = minWidth;
        while (!stab(thin, width, maxPerAxis, points)) {
            if (capped) *capped = true;
            width *= 2.0;
        }
        coords[a].insert(coords[a].end(), points.begin(), points.end());
        if (added) *added += points.size();
    }
    GridSpec refined = spec;
    refined.setCoords(std::move(coords));
    return refined;
}

HermiteGrid castResolvingThinFeatures(const Scene& scene, const Bounds3& bounds, double h,
                                      int threads, uint64_t* rays, ThinPlanes* planes,
                                      const ItemDistributor* distribute) {
    ThinPlanes local;
    ThinPlanes& p = planes ? *planes : local;
    const GridSpec uniform = makeGrid(bounds, h);
    HermiteGrid grid = HermiteGrid::cast(scene, uniform, threads, distribute);
    if (rays) *rays += grid.rays();
    for (int round = 0; round < kThinRounds; ++round) {
        // The allowance left on the tightest axis bounds every axis of this round.
        int allowance = INT32_MAX;
        for (int a = 0; a < 3; ++a)
            allowance = std::min(allowance,
                                 uniform.nodes[a] / 2 - (grid.spec().nodes[a] - uniform.nodes[a]));
        if (allowance <= 0) {
            p.capped = p.capped || grid.thinEdges() > 0;
            break;
        }
        uint64_t added = 0;
        const GridSpec refined =
            withThinPlanes(grid.spec(), grid, tol::kThinMinWidth * h, allowance, &added, &p.capped);
        if (added == 0) break;
        p.added += added;
        ++p.rounds;
        grid = HermiteGrid::cast(scene, refined, threads, distribute);
        if (rays) *rays += grid.rays();
    }
    for (const std::vector<ThinInterval>& axis : grid.thinIntervals()) p.unresolved += axis.size();
    return grid;
}

}  // namespace csg
