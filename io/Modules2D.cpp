// OpenSCAD's 2-D shapes (square, circle, polygon) and the extrusions that lift them
// (linear_extrude, rotate_extrude): see io/Shapes2D.h for how a 2-D shape is kept and
// ../shared/OPENSCAD.md sections 1 to 4 for the semantics followed.
#include "io/Modules2D.h"

#include <cmath>

#include "io/BoundArgs.h"
#include "io/FacetedPrimitives.h"
#include "io/Shapes2D.h"

namespace io {

namespace {

using csg::Extrusion;
using csg::Outline;
using csg::Segment2;
using csg::Vec2;

uint32_t leafTag(Evaluator& e, const InstantiationStmt& s, const GeomState& state) {
    return e.sourceTag(s.loc, e.childPath(state, s.name));
}

Instance shapeLeaf(Evaluator& e, const InstantiationStmt& s, const GeomState& state,
                   Outline outline, const char* shape) {
    return csg::leaf(Extrusion::plane(std::make_shared<Outline>(std::move(outline)), shape),
                     {leafTag(e, s, state), state.material});
}

// The closed polygon through points in order.
void addLoop(Outline& outline, const std::vector<Vec2>& points) {
    for (size_t i = 0; i < points.size(); ++i)
        outline.segments.push_back(Segment2::line(points[i], points[(i + 1) % points.size()]));
}

// A point of polygon(): [x, y] (a third coordinate is ignored, as in OpenSCAD).
std::optional<Vec2> pointOf(const Value& v) {
    if (!v.isVector() || v.list().size() < 2) return std::nullopt;
    const ValueList& l = v.list();
    if (!l[0].isNumber() || !l[1].isNumber()) return std::nullopt;
    const Vec2 p(l[0].number(), l[1].number());
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::nullopt;
    return p;
}

}  // namespace

Instance squareModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"size", "center"}, "square(size, center)");
    Vec2 size(1.0);
    if (b.given(0)) {
        const Value& v = b[0];
        if (v.isNumber() && std::isfinite(v.number())) {
            size = Vec2(v.number());
        } else if (const auto p = pointOf(v); p && v.list().size() == 2) {
            size = *p;
        } else {
            e.warn(b.loc(0), "Unable to convert square(size=" + v.brief() +
                                 ", ...) parameter to a number or a vec2 of numbers");
        }
    }
    const bool center = boolArg(e, b, 1, false);
    if (size.x <= 0 || size.y <= 0) return csg::NodePtr();
    const Vec2 lo = center ? -0.5 * size : Vec2(0.0);
    const Vec2 hi = lo + size;
    Outline outline;
    addLoop(outline, {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}});
    return shapeLeaf(e, s, state, std::move(outline), "square");
}

Instance circleModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"r", "d"}, "circle(r) or circle(d = diameter)");
    const FragmentSettings settings = fragmentSettings(e, b, ctx);
    double r = 1.0;
    if (b.given(1))
        r = 0.5 * numberArg(e, b, 1, 2.0);
    else if (b.given(0))
        r = numberArg(e, b, 0, 1.0);
    if (!(r > 0.0)) return csg::NodePtr();
    Outline outline;
    if (isFaceted(e.curveMode(), settings)) {
        addLoop(outline, circleVertices(r, fragments(r, settings)));
    } else {
        outline.segments.push_back(
            Segment2::arc(Vec2(0.0), Vec2(r, 0.0), Vec2(0.0, r), 0.0, 2.0 * csg::kPi));
    }
    return shapeLeaf(e, s, state, std::move(outline), "circle");
}

Instance polygonModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                       const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"points", "paths", "convexity"},
                           "polygon(points, paths, convexity)");
    if (!b.given(0) || !b[0].isVector()) b.bad(e, 0, "a list of [x, y] points");
    const ValueList& list = b[0].list();
    std::vector<Vec2> points;
    points.reserve(list.size());
    for (const Value& v : list) {
        const auto p = pointOf(v);
        if (!p) b.bad(e, 0, "a list of [x, y] points of finite numbers");
        points.push_back(*p);
    }
    e.spend(s.loc, points.size());
    Outline outline;  // even-odd over all paths, as OpenSCAD's sanitising does
    if (!b.given(1)) {
        if (points.size() >= 3) addLoop(outline, points);
    } else {
        if (!b[1].isVector()) b.bad(e, 1, "a list of paths (lists of point indices)");
        for (const Value& path : b[1].list()) {
            if (!path.isVector()) b.bad(e, 1, "a list of paths (lists of point indices)");
            std::vector<Vec2> loop;
            for (const Value& index : path.list()) {
                const double i = index.isNumber() ? index.number() : -1.0;
                if (!(i >= 0 && i < double(points.size()))) {
                    e.warn(b.loc(1), "polygon(): point index " + index.brief() +
                                         " is out of bounds; skipped, as in OpenSCAD");
                    continue;
                }
                loop.push_back(points[size_t(i)]);
            }
            if (loop.size() >= 3) addLoop(outline, loop);
        }
    }
    if (outline.segments.empty()) return csg::NodePtr();
    return shapeLeaf(e, s, state, std::move(outline), "polygon");
}

namespace {

// The 2-D children of an extrusion; 3-D ones are dropped with OpenSCAD's warning.
Instance shapeChildren(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx,
                       const GeomState& state) {
    Instance children = childrenGroup(e, b, ctx, state);
    if (children && *children && dimensionOf(*children) != 2) {
        e.warn(b.call.loc, b.call.name + "(): its children are 3-D, not 2-D shapes; ignored");
        return csg::NodePtr();
    }
    return children;
}

}  // namespace

Instance linearExtrudeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state) {
    // OpenSCAD 2021's parameter order; a leading unnamed number is the height.
    BoundArgs b = bindArgs(e, s, ctx,
                           {"file", "layer", "height", "origin", "scale", "center", "twist",
                            "slices", "convexity"},
                           "linear_extrude(height, center, convexity, twist, slices, scale)");
    double height = 100.0;
    if (b.given(2))
        height = numberArg(e, b, 2, 100.0);
    else if (b.given(0) && b[0].isNumber())
        height = numberArg(e, b, 0, 100.0);
    else if (b.given(0))
        e.fail(b.loc(0), "linear_extrude(file = ...): DXF files are not supported yet");
    const bool center = boolArg(e, b, 5, false);
    // scale: a number or [sx, sy]; negative factors are 0, as in OpenSCAD.
    Vec2 scale(1.0);
    if (b.given(4)) {
        const Value& v = b[4];
        if (v.isNumber() && std::isfinite(v.number()))
            scale = Vec2(std::max(0.0, v.number()));
        else if (const auto p = pointOf(v))
            scale = glm::max(*p, Vec2(0.0));
        else
            b.bad(e, 4, "a number or [sx, sy]");
    }
    const double twist = numberArg(e, b, 6, 0.0);
    numberArg(e, b, 7, 1.0);  // slices: the exact solid needs none
    Instance shape = shapeChildren(e, b, ctx, state);
    if (!shape || !*shape) return shape;
    if (!(height > 0.0)) return csg::NodePtr();
    const double z0 = center ? -0.5 * height : 0.0;
    return liftLeaves(*shape, [&](const Extrusion& leaf) {
        return leaf.linear(z0, z0 + height, scale, twist);
    });
}

Instance rotateExtrudeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"file", "layer", "origin", "scale", "convexity", "angle"},
                           "rotate_extrude(angle, convexity)");
    if (b.given(0))
        e.fail(b.loc(0), "rotate_extrude(file = ...): DXF files are not supported yet (an "
                         "angle is given as angle = ...)");
    double angle = numberArg(e, b, 5, 360.0);
    if (angle <= -360.0 || angle > 360.0) angle = 360.0;
    Instance shape = shapeChildren(e, b, ctx, state);
    if (!shape || !*shape) return shape;
    if (angle == 0.0) return csg::NodePtr();
    // The profile's half-plane: x >= 0, or a profile wholly in x <= 0 mirrored into it.
    bool mirrored = true;
    bool straddles = false;
    std::function<void(const csg::Node*)> scan = [&](const csg::Node* n) {
        if (!n) return;
        if (n->op != csg::Op::Leaf) return scan(n->left.get()), scan(n->right.get());
        const csg::Bounds2 box = std::get<Extrusion>(n->primitive).box;
        if (box.hi.x > 0.0) mirrored = false;
        if (box.lo.x < 0.0 && box.hi.x > 0.0) straddles = true;
    };
    scan(shape->get());
    (void)straddles;  // the x < 0 part of a straddling leaf lies outside the half-plane
    csg::NodePtr profile = *shape;
    if (mirrored) profile = transformed2D(glm::scale(csg::Mat4(1.0), csg::Vec3(-1, 1, 1)), profile);
    csg::NodePtr solid = liftLeaves(profile, [&](const Extrusion& leaf) {
        return leaf.rotated(std::abs(angle));
    });
    // A negative angle sweeps clockwise: the mirror image in y of the counter-clockwise sweep.
    if (angle < 0.0) solid = csg::transformed(glm::scale(csg::Mat4(1.0), csg::Vec3(1, -1, 1)), solid);
    return solid;
}

}  // namespace io
