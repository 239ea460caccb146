// OpenSCAD 2021's paths of a DXF drawing (src/dxfdata.cc: the two extraction loops at the end
// of DxfData::DxfData, fixup_path_direction and toPolygon2d). Which edges form a path decides
// where an open chain is closed, and the points of one-edge paths are what dxf_cross()
// intersects, so the order is OpenSCAD's: open paths from the lowest-numbered edge with a free
// end (no other remaining edge filed at its node), walking each time to the first remaining
// edge filed at the node reached; then closed paths from the lowest remaining edge.
//
// OpenSCAD rescans every edge for the next free end. Here an edge found not free stays behind
// the scan, and is looked at again only when an edge filed at one of its nodes is used up
// (the only way it can become free): the same paths in n log n.
#include <algorithm>
#include <cmath>
#include <set>

#include "io/DxfGrid.h"

namespace io {

namespace detail {

namespace {

using csg::Vec2;
using Cell = DxfGrid::Cell;

// Cell entries visited before chaining gives up: a node where k edges meet costs k^2.
constexpr uint64_t kMaxChainWork = 2'000'000'000;

class Chainer {
public:
    Chainer(DxfDrawing& drawing, DxfGrid& grid, const std::vector<std::array<Cell*, 2>>& ends)
        : drawing_(drawing),
          ends_(ends),
          n_(int64_t(drawing.edges.size())),
          used_(drawing.edges.size(), 0),
          cellsOf_(drawing.edges.size()) {
        // Every node an edge number is filed at (block lines file numbers at nodes the edge
        // does not touch, and so make it look not free there).
        grid.forEachCell([&](Cell& cell) {
            for (int64_t k : cell)
                if (k < n_ && (cellsOf_[size_t(k)].empty() || cellsOf_[size_t(k)].back() != &cell))
                    cellsOf_[size_t(k)].push_back(&cell);
        });
    }

    std::optional<std::string> run() {
        // Open paths.
        size_t scan = 0;
        for (;;) {
            int64_t found = -1;
            int end = 0;
            while (!recheck_.empty() && found < 0) {
                const int64_t k = *recheck_.begin();
                recheck_.erase(recheck_.begin());
                if (!used_[size_t(k)] && freeEnd(k, end)) found = k;
            }
            for (; found < 0 && scan < size_t(n_); ++scan)
                if (!used_[scan] && freeEnd(int64_t(scan), end)) found = int64_t(scan);
            if (found < 0) break;
            walk(found, end, false, scan);
            if (work_ > kMaxChainWork) return tooMuchWork();
        }
        // Closed paths.
        for (size_t k = 0; k < size_t(n_); ++k) {
            if (!used_[k]) walk(int64_t(k), 0, true, 0);
            if (work_ > kMaxChainWork) return tooMuchWork();
        }
        return std::nullopt;
    }

private:
    Vec2 endOf(int64_t k, int j) const {
        const csg::Segment2& s = drawing_.edges[size_t(k)];
        return j == 0 ? s.start() : s.finish();
    }
    bool remaining(int64_t k) const { return k < n_ && !used_[size_t(k)]; }

    // The first end of edge k (0, then 1) at whose node no other remaining edge is filed.
    bool freeEnd(int64_t k, int& end) {
        for (int j = 0; j < 2; ++j) {
            const Cell& cell = *ends_[size_t(k)][j];
            work_ += cell.size();
            if (std::none_of(cell.begin(), cell.end(),
                             [&](int64_t m) { return m != k && remaining(m); })) {
                end = j;
                return true;
            }
        }
        return false;
    }

    // A path from end `end` of edge k, edge after edge, until the node reached has no
    // remaining edge that ends there. Edges behind `scan` filed at a node of a used edge may
    // have become free: they are looked at again.
    void walk(int64_t k, int end, bool closed, size_t scan) {
        DxfPath path;
        path.closed = closed;
        path.points.push_back(endOf(k, end));
        for (;;) {
            const Vec2 reached = endOf(k, 1 - end);
            path.points.push_back(reached);
            path.edges.push_back(uint32_t(k));
            used_[size_t(k)] = 1;
            if (!closed) {
                for (const Cell* cell : cellsOf_[size_t(k)]) {
                    work_ += cell->size();
                    for (int64_t m : *cell)
                        if (size_t(m) < scan && remaining(m)) recheck_.insert(m);
                }
            }
            const Cell& cell = *ends_[size_t(k)][1 - end];
            work_ += cell.size();
            bool next = false;
            for (int64_t m : cell) {
                if (!remaining(m)) continue;
                for (int j = 0; j < 2 && !next; ++j)
                    if (endOf(m, j) == reached) k = m, end = j, next = true;
                if (next) break;
            }
            if (!next) break;
        }
        drawing_.paths.push_back(std::move(path));
    }

    std::optional<std::string> tooMuchWork() const {
        return "too many edges meet at one point to chain the drawing into paths (" +
               std::to_string(n_) + " edges)";
    }

    DxfDrawing& drawing_;
    const std::vector<std::array<Cell*, 2>>& ends_;
    const int64_t n_;
    std::vector<char> used_;
    std::vector<std::vector<const Cell*>> cellsOf_;
    std::set<int64_t> recheck_;
    uint64_t work_ = 0;
};

// fixup_path_direction: the closed paths (up to the first open one, which in OpenSCAD's order
// means all of them only when there is no open path) turned clockwise by its test at the
// leftmost point. Only dxf_cross() sees the order.
void fixDirections(DxfDrawing& drawing) {
    for (DxfPath& path : drawing.paths) {
        if (!path.closed) break;
        const std::vector<Vec2>& p = path.points;
        size_t b = 0;
        for (size_t j = 1; j < p.size(); ++j)
            if (p[j].x < p[b].x) b = j;
        const size_t a = b == 0 ? p.size() - 2 : b - 1;
        const size_t c = b == p.size() - 1 ? 1 : b + 1;
        const Vec2 ba = p[a] - p[b], bc = p[c] - p[b];
        // atan2(x, y), as OpenSCAD writes it.
        if (std::atan2(ba.x, ba.y) < std::atan2(bc.x, bc.y)) {
            std::reverse(path.points.begin(), path.points.end());
            std::reverse(path.edges.begin(), path.edges.end());
        }
    }
}

}  // namespace

std::optional<std::string> chainPaths(DxfDrawing& drawing, DxfGrid& grid,
                                      const std::vector<std::array<DxfGrid::Cell*, 2>>& ends) {
    if (auto error = Chainer(drawing, grid, ends).run()) return error;
    fixDirections(drawing);
    return std::nullopt;
}

}  // namespace detail

csg::Outline DxfDrawing::outline() const {
    csg::Outline outline;
    outline.rule = csg::FillRule::EvenOdd;
    auto add = [&](const csg::Segment2& s) {
        // A straight edge of no length is never crossed.
        if (s.kind == csg::Segment2::Kind::Line && s.p[0] == s.p[1]) return;
        outline.segments.push_back(s);
    };
    for (const DxfPath& path : paths) {
        const csg::Vec2 first = path.points.front(), last = path.points.back();
        // toPolygon2d: an open path q0 .. qn is the polygon through all its points; a closed
        // one the polygon qn .. q1, which drops q0 and its edge when the walk did not end
        // where it began.
        const bool all = !path.closed || first == last;
        for (size_t i = all ? 0 : 1; i < path.edges.size(); ++i) add(edges[path.edges[i]]);
        if (!path.closed)
            add(csg::Segment2::line(last, first));
        else if (!all)
            add(csg::Segment2::line(path.points[1], last));
    }
    return outline;
}

}  // namespace io
