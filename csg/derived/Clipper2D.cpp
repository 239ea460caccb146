#include "csg/derived/Clipper2D.h"

#include <clipper.hpp>

#include <cmath>
#include <functional>
#include <stdexcept>

#include "csg/derived/Flatten2D.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

namespace cl = ClipperLib;

// OpenSCAD 2021's CLIPPER_SCALE (src/clipper-utils.h): the grid is 2^-16.
constexpr double kScale = 65536.0;
// Clipper's coordinate range (clipper.cpp hiRange) in shape units, with a margin for what an
// offset adds; beyond it Clipper throws.
constexpr double kMaxCoordinate = 4.0e18 / kScale;

// OpenSCAD's ClipperUtils::toPolygon2d: every contour of the tree, cleaned, kept if it still
// has 3 points.
cl::Paths cleaned(const cl::PolyTree& tree) {
    cl::Paths out;
    for (const cl::PolyNode* node = tree.GetFirst(); node; node = node->GetNext()) {
        cl::Path path;
        cl::CleanPolygon(node->Contour, path);
        if (path.size() >= 3) out.push_back(std::move(path));
    }
    return out;
}

class Replay {
public:
    explicit Replay(double tolerance) : tolerance_(tolerance) {}

    // The node's polygons as OpenSCAD holds them after evaluating it (see the header).
    cl::Paths paths(const Node& node, const glm::dmat2& parentM, Vec2 parentShift) {
        const Mat4& local = node.parentFromNode;
        const glm::dmat2 m =
            parentM * glm::dmat2(local[0][0], local[0][1], local[1][0], local[1][1]);
        const Vec2 shift = parentM * Vec2(local[3][0], local[3][1]) + parentShift;
        if (node.op == Op::Leaf) return leaf(node, m, shift);
        const cl::Paths left = node.left ? paths(*node.left, m, shift) : cl::Paths();
        const cl::Paths right = node.right ? paths(*node.right, m, shift) : cl::Paths();
        cl::ClipType type = cl::ctUnion;
        if (node.op == Op::Intersection) type = cl::ctIntersection;
        if (node.op == Op::Difference) type = cl::ctDifference;
        cl::Clipper clipper;
        clipper.AddPaths(left, cl::ptSubject, true);
        clipper.AddPaths(right, cl::ptClip, true);
        cl::PolyTree tree;
        clipper.Execute(type, tree, cl::pftNonZero, cl::pftNonZero);
        return cleaned(tree);
    }

private:
    cl::IntPoint gridPoint(Vec2 p) const {
        if (!(std::abs(p.x) < kMaxCoordinate) || !(std::abs(p.y) < kMaxCoordinate))
            throw std::range_error("a 2-D coordinate beyond Clipper's range (about 7e13)");
        // The conversion truncates towards zero, as OpenSCAD's emplace_back(double, double)
        // into an IntPoint of integers does.
        return cl::IntPoint(cl::cInt(p.x * kScale), cl::cInt(p.y * kScale));
    }

    cl::Paths leaf(const Node& node, const glm::dmat2& m, Vec2 shift) const {
        const auto* e = std::get_if<Extrusion>(&node.primitive);
        if (!e || !e->outline) return {};
        const Outline outline = e->outline->mapped(m, shift);
        // The outline's segments run in closed curves one after another (io/Modules2D.cpp
        // addLoop, the bands of Offset2D.cpp): a curve ends where the next segment does not
        // start where the last one finished.
        cl::Paths loops;
        std::vector<Vec2> points;
        auto flush = [&] {
            cl::Path path;
            for (const Vec2& p : points) path.push_back(gridPoint(p));
            if (path.size() >= 3) loops.push_back(std::move(path));
            points.clear();
        };
        for (size_t i = 0; i < outline.segments.size(); ++i) {
            const Segment2& s = outline.segments[i];
            if (i > 0 && s.start() != outline.segments[i - 1].finish()) flush();
            appendChordPoints(s, tolerance_, points);
        }
        flush();
        // OpenSCAD sanitizes every 2-D leaf as it is made (GeometryEvaluator::visit(LeafNode)).
        const cl::PolyFillType fill =
            outline.rule == FillRule::EvenOdd ? cl::pftEvenOdd : cl::pftNonZero;
        cl::Clipper clipper;
        clipper.AddPaths(loops, cl::ptSubject, true);
        cl::PolyTree tree;
        clipper.Execute(cl::ctUnion, tree, fill, fill);
        return cleaned(tree);
    }

    double tolerance_;
};

// The largest coordinate of the shape's leaves (at least 1): the scale of its chord tolerance.
double sizeOf(const Node& shape) {
    double size = 1.0;
    std::function<void(const Node&)> measure = [&](const Node& n) {
        if (n.op == Op::Leaf) {
            if (const auto* e = std::get_if<Extrusion>(&n.primitive); e && !e->box.empty())
                size = std::max({size, std::abs(e->box.lo.x), std::abs(e->box.lo.y),
                                 std::abs(e->box.hi.x), std::abs(e->box.hi.y)});
            return;
        }
        if (n.left) measure(*n.left);
        if (n.right) measure(*n.right);
    };
    measure(shape);
    return size;
}

// The shape's polygons as OpenSCAD holds them (see the header).
cl::Paths polygonsOf(const Node& shape) {
    Replay replay(tol::kFlattenRel * sizeOf(shape));
    return replay.paths(shape, glm::dmat2(1.0), Vec2(0.0));
}

// A Clipper result as one outline: outer curves counter-clockwise, holes clockwise, so
// even-odd is exact.
Outline outlineOf(const cl::PolyTree& tree) {
    Outline out;
    for (const cl::Path& path : cleaned(tree)) {
        for (size_t i = 0; i < path.size(); ++i) {
            const cl::IntPoint& p = path[i];
            const cl::IntPoint& q = path[(i + 1) % path.size()];
            out.segments.push_back(
                Segment2::line(Vec2(double(p.X) / kScale, double(p.Y) / kScale),
                               Vec2(double(q.X) / kScale, double(q.Y) / kScale)));
        }
    }
    return out;
}

// Runs a Clipper computation, turning its exceptions into `error`.
template <class F>
std::optional<Outline> guarded(std::string& error, F&& compute) {
    try {
        return compute();
    } catch (const std::exception& x) {
        error = x.what();
    } catch (...) {
        // Clipper 6 throws a clipperException (or, before 6.2.2, a char*) on a range error.
        error = "Clipper refused the polygons (coordinates beyond its range)";
    }
    return std::nullopt;
}

// OpenSCAD's fill_minkowski_insides: every path of a moved by the first point of each
// counter-clockwise path of b.
void fillInsides(const cl::Paths& a, const cl::Paths& b, cl::Paths& target) {
    for (const cl::Path& bPath : b) {
        if (bPath.empty() || !cl::Orientation(bPath)) continue;
        const cl::IntPoint delta = bPath[0];
        for (const cl::Path& path : a) {
            target.push_back(path);
            for (cl::IntPoint& p : target.back()) {
                p.X += delta.X;
                p.Y += delta.Y;
            }
        }
    }
}

}  // namespace

std::optional<Outline> clipperOffset(const Node& shape, const ClipperOffsetSpec& spec,
                                     std::string& error) {
    return guarded(error, [&] {
        const cl::Paths input = polygonsOf(shape);
        cl::JoinType join = cl::jtRound;
        if (spec.join == OffsetJoin::Miter) join = cl::jtMiter;
        if (spec.join == OffsetJoin::Chamfer) join = cl::jtSquare;
        // OpenSCAD's OffsetNode: miter limit 1e6; the arc tolerance scaled onto the grid.
        cl::ClipperOffset offset(1e6, spec.arcTolerance * kScale);
        offset.AddPaths(input, join, cl::etClosedPolygon);
        cl::PolyTree tree;
        offset.Execute(tree, spec.delta * kScale);
        return outlineOf(tree);
    });
}

std::optional<Outline> clipperMinkowski(const Node& a, const Node& b, std::string& error) {
    return guarded(error, [&] {
        const cl::Paths lhs = polygonsOf(a), rhs = polygonsOf(b);
        cl::Paths terms;
        for (const cl::Path& r : rhs)
            for (const cl::Path& l : lhs) {
                cl::Paths swept;
                cl::MinkowskiSum(l, r, swept, true);
                terms.insert(terms.end(), swept.begin(), swept.end());
            }
        fillInsides(lhs, rhs, terms);
        fillInsides(rhs, lhs, terms);
        cl::Clipper clipper;
        clipper.AddPaths(terms, cl::ptSubject, true);
        cl::PolyTree tree;
        clipper.Execute(cl::ctUnion, tree, cl::pftNonZero, cl::pftNonZero);
        return outlineOf(tree);
    });
}

}  // namespace csg
