// OpenSCAD's 2-D shapes (square, circle, polygon) and the extrusions that lift them
// (linear_extrude, rotate_extrude): see io/Shapes2D.h for how a 2-D shape is kept and
// ../shared/OPENSCAD.md sections 1 to 4 for the semantics followed.
#include "io/Modules2D.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "csg/derived/Boundary2D.h"
#include "csg/derived/Flatten2D.h"
#include "io/BoundArgs.h"
#include "io/Degrees.h"
#include "io/DxfModules.h"
#include "io/ExtrusionMesh.h"
#include "io/FacetedPrimitives.h"
#include "io/Shapes2D.h"
#include "primitives/base/Tolerances.h"

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
    outline.buildIndex();
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
        outline.segments.push_back(Segment2::circle(Vec2(0.0), r));
    }
    return shapeLeaf(e, s, state, std::move(outline), "circle");
}

Instance polygonModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                       const GeomState& state) {
    BoundArgs b =
        bindArgs(e, s, ctx, {"points", "paths", "convexity"}, "polygon(points, paths, convexity)");
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

// OpenSCAD 2021's legacy file = of the extrusions: the drawing instead of the children, with
// its deprecation warning.
Instance legacyDxfShape(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx,
                        const GeomState& state, const DxfArgs& args) {
    e.warn(b.loc(args.file), "DEPRECATED: Support for reading files in " + b.call.name +
                                 " will be removed in future releases. Use a child import() "
                                 "instead.");
    if (!b.call.children.empty())
        e.warn(b.call.loc, b.call.name + "(file = ...): its children are ignored, as in OpenSCAD");
    return dxfShape(e, b, ctx, state, args);
}

// What OpenSCAD's sliced linear_extrude reads (OPENSCAD.md section 3).
struct SlicedExtrusionArgs {
    double z0, z1;
    double twist;
    Vec2 scale;
    int64_t slices;  // given by the call when above 0
    FragmentSettings settings;
};

// OpenSCAD 2021's sliced solid of a twisted or unevenly scaled linear_extrude (--curves
// openscad): the polyhedron it builds, as a leaf. Null, with a warning, when the profile does
// not close into polygons or its slices into a solid: the caller keeps the exact solid.
csg::NodePtr slicedExtrusion(Evaluator& e, const InstantiationStmt& s, const csg::NodePtr& shape,
                             const SlicedExtrusionArgs& a) {
    const auto keepExact = [&](const std::string& why) {
        e.warn(s.loc, "linear_extrude(): OpenSCAD's sliced solid is not built (" + why +
                          "); the exact twisted solid stands in for it");
        return csg::NodePtr();
    };
    // The profile's boundary as closed contours, as OpenSCAD extrudes the union of the
    // children (a leaf too: an imported drawing's segments need not chain as they come).
    const std::optional<BoundaryOutline> united = boundaryOutline(*shape);
    std::optional<std::vector<RegionPolygon>> region;
    if (united) {
        const csg::Bounds2 box = united->outline->bounds();
        const double size = std::max(
            {std::abs(box.lo.x), std::abs(box.lo.y), std::abs(box.hi.x), std::abs(box.hi.y), 1.0});
        region = chordRegion(*united->outline, box, csg::tol::kFlattenRel * size);
    }
    if (!region) return keepExact("its profile does not close into polygons");
    // The slices OpenSCAD counts from the profile's vertices, and what they make.
    double rmaxSquared = 0.0, deltaSquared = 0.0;
    uint64_t corners = 0;
    const auto scan = [&](const std::vector<Vec2>& contour) {
        for (const Vec2& v : contour) {
            rmaxSquared = std::fmax(rmaxSquared, glm::dot(v, v));
            const Vec2 moved = v - v * a.scale;
            deltaSquared = std::fmax(deltaSquared, glm::dot(moved, moved));
        }
        corners += contour.size();
    };
    for (const RegionPolygon& polygon : *region) {
        scan(polygon.outer);
        for (const std::vector<Vec2>& hole : polygon.holes) scan(hole);
    }
    const int64_t slices = a.slices > 0 ? a.slices
                                        : extrudeSlices(rmaxSquared, deltaSquared, a.z1 - a.z0,
                                                        a.twist, a.scale, a.settings);
    const uint64_t triangles = 2 * uint64_t(slices) * corners;
    if (triangles > csg::Polyhedron::kMaxTriangles)
        e.fail(s.loc, "linear_extrude(): " + std::to_string(slices) + " slices of " +
                          std::to_string(corners) + " corners make " + std::to_string(triangles) +
                          " triangles; OpenSCAD's sliced solid (--curves openscad) may have at "
                          "most " +
                          std::to_string(csg::Polyhedron::kMaxTriangles) +
                          "; expected fewer slices (slices, $fn, or a larger $fa or $fs), or "
                          "--curves auto for the exact solid");
    // A triangle and a point for each corner and slice, as polyhedron() charges them.
    e.spend(s.loc, 2 * triangles);
    std::optional<csg::Polyhedron> mesh =
        slicedExtrusionMesh(*region, a.z0, a.z1, a.twist, a.scale, slices);
    if (!mesh) return keepExact("its slices do not close into a solid");
    return csg::leaf(std::move(*mesh), shape->tags);
}

}  // namespace

Instance linearExtrudeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state) {
    // OpenSCAD 2021's parameter order; a leading unnamed number is the height.
    BoundArgs b = bindArgs(
        e, s, ctx,
        {"file", "layer", "height", "origin", "scale", "center", "twist", "slices", "convexity"},
        "linear_extrude(height, center, convexity, twist, slices, scale)");
    const bool fromFile = b.given(0) && b[0].isString();
    double height = 100.0;
    if (b.given(2))
        height = numberArg(e, b, 2, 100.0);
    else if (b.given(0) && b[0].isNumber())
        height = numberArg(e, b, 0, 100.0);
    else if (b.given(0) && !fromFile)
        b.bad(e, 0, "a DXF file name (OpenSCAD 2021's legacy file = ...) or the height");
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
    // slices: read by OpenSCAD's sliced solid only (the exact one needs none); OpenSCAD takes
    // its integer part when that is above 0.
    const double slices = numberArg(e, b, 7, 0.0);
    // OpenSCAD 2021 reads the drawing with the extrusion's scale (so it also scales the
    // drawing) and ignores the children.
    Instance shape = fromFile ? legacyDxfShape(e, b, ctx, state, DxfArgs{0, 1, 3, scale.x})
                              : shapeChildren(e, b, ctx, state);
    if (!shape || !*shape) return shape;
    if (!(height > 0.0)) return csg::NodePtr();
    const double z0 = center ? -0.5 * height : 0.0;
    // A twisted line finds its pieces per leaf: one leaf for the whole profile, as OpenSCAD
    // extrudes the union of the children.
    if (twist != 0.0 || scale.x != scale.y) {
        shape = unitedShape(*shape);
        if (!*shape) return shape;
        if (e.solidCurveMode() == CurveMode::OpenScad) {
            const SlicedExtrusionArgs args{
                z0,
                z0 + height,
                twist,
                scale,
                std::isfinite(slices) ? int64_t(std::clamp(std::trunc(slices), 0.0, 0x1p31)) : 0,
                unclampedFragmentSettings(e, b, ctx)};
            if (csg::NodePtr sliced = slicedExtrusion(e, s, *shape, args)) return sliced;
        }
    }
    return liftLeaves(
        *shape, [&](const Extrusion& leaf) { return leaf.linear(z0, z0 + height, scale, twist); });
}

namespace {

// The colour of a profile's revolution: its first leaf's (a part colours a profile as a whole).
// The sectors' boxes and half-spaces take it too: a profile's flat top or bottom lies in its
// sector box's face, and the merge names the box there (the first operand).
uint32_t profileMaterial(const csg::NodePtr& profile) {
    const csg::Node* leaf = profile.get();
    while (leaf->op != csg::Op::Leaf) leaf = leaf->left.get();
    return leaf->tags.material;
}

// OpenSCAD's faceted revolution (OPENSCAD.md section 4): `sections` sectors of equal angle
// from azimuth `start`. Between two rings every profile vertex (r, z) becomes a chord at
// distance r cos(delta/2) from the axis along the sector's bisector m, so the sector is
// exactly the wedge cut from the prism {p : ((p . m) / cos(delta/2), p.z) in profile}: the
// profile's 2-D tree lifted into that plane by a linear map, no triangles needed.
csg::NodePtr facetedRevolution(const csg::NodePtr& profile, double start, double angle,
                               int64_t sections, double rmax, double zlo, double zhi,
                               uint32_t tag) {
    const double delta = angle / double(sections);
    const double reach = 2.0 * rmax + 1.0;  // past the wedge's width at any radius
    const csg::Tags tags{tag, profileMaterial(profile)};
    const csg::NodePtr prism = liftLeaves(
        profile, [&](const Extrusion& leaf) { return leaf.linear(-reach, reach, Vec2(1.0)); });
    std::vector<csg::NodePtr> sectors;
    sectors.reserve(size_t(sections));
    for (int64_t j = 0; j < sections; ++j) {
        const double a0 = start + double(j) * delta, a1 = a0 + delta, mid = a0 + 0.5 * delta;
        const csg::Vec3 m(cosDegrees(mid), sinDegrees(mid), 0.0);
        const csg::Vec3 w(-m.y, m.x, 0.0);
        const double c = cosDegrees(0.5 * delta);
        // Local (u, v, s) = ((p . m) / c, p.z, p . w): world = u c m + v z + s w.
        csg::Mat4 worldFromLocal(1.0);
        worldFromLocal[0] = csg::Vec4(c * m, 0.0);
        worldFromLocal[1] = csg::Vec4(0.0, 0.0, 1.0, 0.0);
        worldFromLocal[2] = csg::Vec4(w, 0.0);
        const csg::NodePtr after =
            csg::leaf(csg::HalfSpace{csg::Vec3(sinDegrees(a0), -cosDegrees(a0), 0.0), 0.0}, tags);
        const csg::NodePtr before =
            csg::leaf(csg::HalfSpace{csg::Vec3(-sinDegrees(a1), cosDegrees(a1), 0.0), 0.0}, tags);
        // The sector's box (the triangle from the axis to its outer chord, times the
        // profile's height) keeps its bounds tight for the BVH.
        const csg::Vec2 e0(cosDegrees(a0), sinDegrees(a0)), e1(cosDegrees(a1), sinDegrees(a1));
        const csg::Vec2 lo = glm::min(csg::Vec2(0.0), rmax * glm::min(e0, e1));
        const csg::Vec2 hi = glm::max(csg::Vec2(0.0), rmax * glm::max(e0, e1));
        const csg::NodePtr box = csg::leaf(csg::Box{csg::Vec3(lo, zlo), csg::Vec3(hi, zhi)}, tags);
        sectors.push_back(
            csg::intersectAll({box, after, before, csg::transformed(worldFromLocal, prism)}, tags));
    }
    return csg::uniteAll(sectors, tags);
}

// The faceted revolution as one polyhedron, OpenSCAD's own mesh of it, when the profile's
// boundary is straight lines in x >= 0; nullptr otherwise (an exact circle() in a revolution
// with $fn keeps the sector wedges, which take any profile). One leaf instead of a union of
// sectors: rays walk one mesh's BVH, and the export takes its exact boundary.
csg::NodePtr revolutionPolyhedron(const csg::NodePtr& profile, double start, double angle,
                                  int64_t sections, uint32_t tag) {
    const std::optional<BoundaryOutline> united = boundaryOutline(*profile);
    if (!united || united->approximated || !csg::straightEdged(*united->outline)) return nullptr;
    const csg::Bounds2 box = united->outline->bounds();
    if (box.empty() || box.lo.x < 0.0) return nullptr;
    // Lines only: the chords' deviation is never used.
    const std::optional<std::vector<RegionPolygon>> region =
        chordRegion(*united->outline, box, 1.0);
    if (!region) return nullptr;
    std::optional<csg::Polyhedron> mesh = facetedRevolutionMesh(*region, start, angle, sections);
    if (!mesh) return nullptr;
    return csg::leaf(std::move(*mesh), {tag, profileMaterial(profile)});
}

}  // namespace

Instance rotateExtrudeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"file", "layer", "origin", "scale", "convexity", "angle"},
                           "rotate_extrude(angle, convexity)");
    if (b.given(0) && !b[0].isString())
        b.bad(e, 0,
              "a DXF file name (OpenSCAD 2021's first parameter is the legacy file; an "
              "angle is given as angle = ...)");
    const FragmentSettings settings = fragmentSettings(e, b, ctx);
    double angle = numberArg(e, b, 5, 360.0);
    if (angle <= -360.0 || angle > 360.0) angle = 360.0;
    Instance shape;
    if (b.given(0)) {
        // The drawing's scale: OpenSCAD takes one that is not above 0 as 1.
        double scale = numberArg(e, b, 3, 1.0);
        if (scale <= 0.0) scale = 1.0;
        shape = legacyDxfShape(e, b, ctx, state, DxfArgs{0, 1, 2, scale});
    } else {
        shape = shapeChildren(e, b, ctx, state);
    }
    if (!shape || !*shape) return shape;
    if (angle == 0.0) return csg::NodePtr();
    // The profile's half-plane: x >= 0, or a profile wholly in x <= 0 mirrored into it. A
    // leaf may reach across x = 0 (the revolution reads the half-plane x >= 0 only); the
    // profile itself may not, as OpenSCAD says (OPENSCAD.md section 4).
    csg::Bounds2 leaves;
    double rmax = 0.0, zlo = csg::kInfinity, zhi = -csg::kInfinity;
    std::function<void(const csg::Node*)> scan = [&](const csg::Node* n) {
        if (!n) return;
        if (n->op != csg::Op::Leaf) return scan(n->left.get()), scan(n->right.get());
        const csg::Bounds2 box = std::get<Extrusion>(n->primitive).box;
        leaves.add(box.lo);
        leaves.add(box.hi);
        rmax = std::max({rmax, std::abs(box.lo.x), std::abs(box.hi.x)});
        zlo = std::min(zlo, box.lo.y), zhi = std::max(zhi, box.hi.y);
    };
    scan(shape->get());
    bool mirrored = leaves.hi.x <= 0.0;
    if (leaves.lo.x < 0.0 && leaves.hi.x > 0.0) {
        const csg::Region2D region(**shape);
        csg::Bounds2 profile;
        for (const csg::BoundaryPiece& p : csg::boundaryOf(region).pieces) {
            const csg::Bounds2 piece = p.bounds();
            profile.add(piece.lo);
            profile.add(piece.hi);
        }
        const double eps = csg::tol::kBoundaryPointRel * region.size();
        if (profile.lo.x < -eps && profile.hi.x > eps) {
            char range[64];
            std::snprintf(range, sizeof range, "%.2f -> %.2f", profile.lo.x, profile.hi.x);
            e.fail(s.loc,
                   "all points for rotate_extrude() must have the same X coordinate sign "
                   "(range is " +
                       std::string(range) + ")");
        }
        mirrored = profile.hi.x <= eps;
    }
    // A profile with no height (BOSL2's bottle adapter revolves a polygon of zero thickness)
    // or on the axis sweeps no volume: the empty solid, as OpenSCAD makes nothing of it.
    if (!(zhi > zlo) || !(rmax > 0.0)) return csg::NodePtr();
    csg::NodePtr profile = *shape;
    if (mirrored) profile = transformed2D(glm::scale(csg::Mat4(1.0), csg::Vec3(-1, 1, 1)), profile);
    csg::NodePtr solid;
    if (isFaceted(e.solidCurveMode(), settings)) {
        // OpenSCAD 2021's rings: a full turn starts on -x.
        const double sweep = std::abs(angle);
        const int64_t sections =
            std::max<int64_t>(int64_t(double(fragments(rmax, settings)) * sweep / 360.0), 1);
        const double start = sweep == 360.0 ? 180.0 : 0.0;
        const uint32_t tag = e.sourceTag(s.loc, e.childPath(state, s.name));
        solid = revolutionPolyhedron(profile, start, sweep, sections, tag);
        if (!solid) solid = facetedRevolution(profile, start, sweep, sections, rmax, zlo, zhi, tag);
    } else {
        solid = liftLeaves(profile,
                           [&](const Extrusion& leaf) { return leaf.rotated(std::abs(angle)); });
    }
    // OpenSCAD maps a profile point (x, y) to (x cos a, x sin a, y) even for x < 0: the
    // mirrored profile's solid lies half a turn round.
    if (mirrored)
        solid = csg::transformed(glm::rotate(csg::Mat4(1.0), csg::kPi, csg::Vec3(0, 0, 1)), solid);
    // A negative angle sweeps clockwise: the mirror image in y of the counter-clockwise sweep.
    if (angle < 0.0)
        solid = csg::transformed(glm::scale(csg::Mat4(1.0), csg::Vec3(1, -1, 1)), solid);
    return solid;
}

}  // namespace io
