#include "csg/mesh/HermiteGrid.h"

#include <algorithm>
#include <cmath>

#include "csg/mesh/ParallelFor.h"

namespace csg {

GridSpec makeGrid(const Bounds3& bounds, double h) {
    // An irrational fraction of a cell (1/pi) plus the quarter-cell margin: nodes keep off
    // faces at round coordinates, and the boundary nodes stay strictly outside the bounds.
    constexpr double kShift = 0.25 + 0.3183098861837907;
    GridSpec spec;
    spec.h = h;
    spec.origin = bounds.lo - Vec3(kShift * h);
    for (int a = 0; a < 3; ++a) {
        const double span = bounds.hi[a] + 0.25 * h - spec.origin[a];
        spec.nodes[a] = std::max(2, int(std::ceil(span / h)) + 1);
    }
    return spec;
}

namespace {

// The other two axes of a line of axis a, in right-handed order (a, b, c).
inline int nextAxis(int a) {
    return (a + 1) % 3;
}
inline int prevAxis(int a) {
    return (a + 2) % 3;
}

// What one row of lines (fixed coordinate c) produced: crossings of its lines back to back.
struct RowResult {
    std::vector<Crossing> crossings;
    std::vector<uint32_t> counts;  // per line of the row
    uint64_t thinEdges = 0;        // see HermiteGrid::thinEdges()
    Vec3 thinAt{0.0};
};

}  // namespace

HermiteGrid HermiteGrid::cast(const Scene& scene, const GridSpec& spec, int threads) {
    HermiteGrid grid;
    grid.spec_ = spec;
    grid.inside_.assign(spec.nodeCount(), 0);
    const int workers = resolveThreads(threads);
    std::vector<QueryContext> contexts(static_cast<size_t>(workers));
    uint64_t rays = 0;

    for (int a = 0; a < 3; ++a) {
        const int b = nextAxis(a), c = prevAxis(a);
        const int along = spec.nodes[a], nb = spec.nodes[b], nc = spec.nodes[c];
        std::vector<RowResult> rows(static_cast<size_t>(nc));
        Vec3 dir(0.0);
        dir[a] = 1.0;

        // Cast: each row of lines on one worker; the ray runs from one cell before node 0 to
        // one cell after the last node, so every span end inside the grid is a surface.
        parallelFor(uint64_t(nc), workers, [&](int worker, uint64_t rowIndex) {
            QueryContext& ctx = contexts[size_t(worker)];
            RowResult& row = rows[rowIndex];
            row.counts.assign(size_t(nb), 0);
            std::array<int, 3> node{};
            node[c] = int(rowIndex);
            for (int ib = 0; ib < nb; ++ib) {
                node[b] = ib;
                node[a] = 0;
                Ray ray;
                ray.o = spec.node(node[0], node[1], node[2]) - spec.h * dir;
                ray.d = dir;
                ray.tmin = 0.0;
                ray.tmax = (along + 1) * spec.h;
                const std::span<const Span> spans = scene.spans(ray, ctx);
                const size_t before = row.crossings.size();
                for (const Span& s : spans) {
                    for (const Hit* hit : {&s.in, &s.out}) {
                        if (!hit->isSurface()) continue;
                        const SurfacePoint sp = scene.surface(ray, *hit);
                        row.crossings.push_back(
                            {sp.point, sp.normal, hit->t, scene.leafTags(hit->leaf).material});
                    }
                }
                row.counts[size_t(ib)] = uint32_t(row.crossings.size() - before);
                // Two crossings on one grid edge: a wall or gap thinner than the cell there.
                for (size_t x = before + 1; x < row.crossings.size(); ++x) {
                    const Crossing &p = row.crossings[x - 1], &q = row.crossings[x];
                    if (std::ceil(p.t / spec.h) != std::ceil(q.t / spec.h)) continue;
                    if (row.thinEdges++ == 0) row.thinAt = 0.5 * (p.point + q.point);
                }
                // Signs from the z lines only: one authority per node keeps cells consistent.
                if (a == 2) {
                    size_t s = 0;
                    for (int n = 0; n < along; ++n) {
                        const double t = (n + 1) * spec.h;
                        while (s < spans.size() && spans[s].out.t < t) ++s;
                        if (s < spans.size() && spans[s].in.t <= t) {
                            node[a] = n;
                            grid.inside_[node[0] +
                                         size_t(spec.nodes[0]) *
                                             (node[1] + size_t(spec.nodes[1]) * node[2])] = 1;
                        }
                    }
                }
            }
        });

        // Gather: rows in order into one array per axis with line offsets.
        std::vector<Crossing>& all = grid.crossings_[size_t(a)];
        std::vector<uint64_t>& start = grid.lineStart_[size_t(a)];
        size_t total = 0;
        for (const RowResult& row : rows) total += row.crossings.size();
        all.reserve(total);
        start.reserve(size_t(nb) * nc + 1);
        start.push_back(0);
        for (RowResult& row : rows) {
            if (row.thinEdges && grid.thinEdges_ == 0) grid.thinAt_ = row.thinAt;
            grid.thinEdges_ += row.thinEdges;
            all.insert(all.end(), row.crossings.begin(), row.crossings.end());
            for (uint32_t count : row.counts) start.push_back(start.back() + count);
            row = RowResult{};
        }
        rays += uint64_t(nb) * nc;
    }
    grid.rays_ = rays;
    return grid;
}

const Crossing* HermiteGrid::crossing(int axis, std::array<int, 3> node) const {
    const int b = nextAxis(axis), c = prevAxis(axis);
    const uint64_t line = uint64_t(node[b]) + uint64_t(spec_.nodes[b]) * uint64_t(node[c]);
    const std::vector<Crossing>& all = crossings_[size_t(axis)];
    const auto first = all.begin() + int64_t(lineStart_[size_t(axis)][line]);
    const auto last = all.begin() + int64_t(lineStart_[size_t(axis)][line + 1]);
    const double t0 = (node[axis] + 1) * spec_.h, t1 = (node[axis] + 2) * spec_.h;
    const auto it =
        std::upper_bound(first, last, t0, [](double t, const Crossing& x) { return t < x.t; });
    if (it == last || it->t > t1) return nullptr;
    return &*it;
}

}  // namespace csg
