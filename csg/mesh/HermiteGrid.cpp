#include "csg/mesh/HermiteGrid.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg {

GridSpec makeGrid(const Bounds3& bounds, double h) {
    // An irrational fraction of a cell (1/pi) plus the quarter-cell margin: nodes keep off
    // faces at round coordinates, and the boundary nodes stay strictly outside the bounds.
    constexpr double kShift = 0.25 + 0.3183098861837907;
    GridSpec spec;
    spec.h = h;
    const Vec3 origin = bounds.lo - Vec3(kShift * h);
    std::array<std::vector<double>, 3> coords;
    for (int a = 0; a < 3; ++a) {
        const double span = bounds.hi[a] + 0.25 * h - origin[a];
        const int count = std::max(2, int(std::ceil(span / h)) + 1);
        coords[size_t(a)].resize(size_t(count));
        for (int n = 0; n < count; ++n) coords[size_t(a)][size_t(n)] = origin[a] + h * n;
    }
    spec.setCoords(std::move(coords));
    return spec;
}

double GridSpec::cellMinWidth(int i, int j, int k) const {
    const std::array<int, 3> at{i, j, k};
    double width = h;
    for (size_t a = 0; a < 3; ++a)
        width = std::min(width, coords[a][size_t(at[a]) + 1] - coords[a][size_t(at[a])]);
    return width;
}

void GridSpec::setCoords(std::array<std::vector<double>, 3> c) {
    for (size_t a = 0; a < 3; ++a) {
        std::sort(c[a].begin(), c[a].end());
        c[a].erase(std::unique(c[a].begin(), c[a].end()), c[a].end());
        nodes[a] = int(c[a].size());
    }
    coords = std::move(c);
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
    std::vector<ThinInterval> thin;  // see HermiteGrid::thinIntervals()
};

}  // namespace

HermiteGrid HermiteGrid::cast(const Scene& scene, const GridSpec& spec, int threads,
                              const ItemDistributor* distribute) {
    HermiteGrid grid;
    grid.spec_ = spec;
    grid.inside_.assign(spec.nodeCount(), 0);
    const int workers = workersFor(distribute, threads);
    std::vector<QueryContext> contexts(static_cast<size_t>(workers));
    uint64_t rays = 0;

    for (int a = 0; a < 3; ++a) {
        const int b = nextAxis(a), c = prevAxis(a);
        const int along = spec.nodes[a], nb = spec.nodes[b], nc = spec.nodes[c];
        std::vector<RowResult> rows(static_cast<size_t>(nc));
        Vec3 dir(0.0);
        dir[a] = 1.0;
        const std::vector<double>& lineNodes = spec.coords[size_t(a)];
        const double lineStart = lineNodes.front() - spec.h;
        // The edge of the line holding ray parameter t: node n with t in (t(n), t(n + 1)].
        auto edgeOf = [&](double t) {
            return std::lower_bound(lineNodes.begin(), lineNodes.end(), t + lineStart) -
                   lineNodes.begin();
        };

        // Cast: each row of lines on one worker; the ray runs from one cell before node 0 to
        // one cell after the last node, so every span end inside the grid is a surface. The
        // nodes a z row finds inside go to `inside` (as indices into inside_).
        auto castRow = [&](int worker, uint64_t rowIndex, RowResult& row,
                           std::vector<uint64_t>& inside) {
            QueryContext& ctx = contexts[size_t(worker)];
            row.counts.assign(size_t(nb), 0);
            std::array<int, 3> node{};
            node[c] = int(rowIndex);
            for (int ib = 0; ib < nb; ++ib) {
                node[b] = ib;
                node[a] = 0;
                Ray ray;
                ray.o = spec.node(node[0], node[1], node[2]);
                ray.o[a] = lineStart;
                ray.d = dir;
                ray.tmin = 0.0;
                ray.tmax = lineNodes.back() - lineStart + spec.h;
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
                    if (edgeOf(p.t) != edgeOf(q.t)) continue;
                    if (row.thinEdges++ == 0) row.thinAt = 0.5 * (p.point + q.point);
                    if (glm::dot(p.normal, q.normal) < tol::kThinFacingCos)
                        row.thin.push_back({p.point[a], q.point[a]});
                }
                // Signs from the z lines only: one authority per node keeps cells consistent.
                if (a == 2) {
                    size_t s = 0;
                    for (int n = 0; n < along; ++n) {
                        const double t = spec.lineT(a, n);
                        while (s < spans.size() && spans[s].out.t < t) ++s;
                        if (s < spans.size() && spans[s].in.t <= t) {
                            node[a] = n;
                            inside.push_back(node[0] +
                                             size_t(spec.nodes[0]) *
                                                 (node[1] + size_t(spec.nodes[1]) * node[2]));
                        }
                    }
                }
            }
        };
        const auto setInside = [&](const std::vector<uint64_t>& inside) {
            for (const uint64_t i : inside) grid.inside_[i] = 1;
        };
        if (!distribute) {
            parallelFor(uint64_t(nc), workers, [&](int worker, uint64_t rowIndex) {
                std::vector<uint64_t> inside;
                castRow(worker, rowIndex, rows[rowIndex], inside);
                setInside(inside);  // rows set disjoint nodes
            });
        } else {
            distribute->run(
                uint64_t(nc), "the grid's rows",
                [&](int worker, uint64_t rowIndex, std::string& bytes) {
                    RowResult row;
                    std::vector<uint64_t> inside;
                    castRow(worker, rowIndex, row, inside);
                    ByteWriter out(bytes);
                    out.values(row.crossings);
                    out.values(row.counts);
                    out.value(row.thinEdges);
                    out.value(row.thinAt);
                    out.values(row.thin);
                    out.values(inside);
                },
                [&](uint64_t rowIndex, std::string_view bytes) {
                    ByteReader in(bytes);
                    RowResult& row = rows[rowIndex];
                    row.crossings = in.values<Crossing>();
                    row.counts = in.values<uint32_t>();
                    row.counts.resize(size_t(nb), 0);  // whatever came, one count a line
                    row.thinEdges = in.value<uint64_t>();
                    row.thinAt = in.value<Vec3>();
                    row.thin = in.values<ThinInterval>();
                    setInside(in.values<uint64_t>());
                });
        }

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
            grid.thin_[size_t(a)].insert(grid.thin_[size_t(a)].end(), row.thin.begin(),
                                         row.thin.end());
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
    const double t0 = spec_.lineT(axis, node[axis]), t1 = spec_.lineT(axis, node[axis] + 1);
    const auto it =
        std::upper_bound(first, last, t0, [](double t, const Crossing& x) { return t < x.t; });
    if (it == last || it->t > t1) return nullptr;
    return &*it;
}

}  // namespace csg
