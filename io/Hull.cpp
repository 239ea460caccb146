// hull(): of 2-D children the exact hull of their points and arcs (csg/derived/Hull2D.h), of
// 3-D children qhull's hull of the vertices of their result (csg/derived/Hull3D.h), as OpenSCAD
// 2021's applyHull2D and CGALUtils::applyHull. The children are evaluated with curved solids
// faceted as OpenSCAD facets them (Evaluator::solidCurveMode): a sphere has no vertices, its
// faceted polyhedron does, and those are what OpenSCAD hulls. Curves that are still exact in
// a 3-D hull (a linear_extrude of an exact circle, csgray's torus) are faceted here with the
// hull's own $fn, $fa, $fs, which the children inherit unless they set their own.
#include <cmath>
#include <memory>

#include "csg/derived/Flatten2D.h"
#include "csg/derived/Hull2D.h"
#include "csg/derived/Hull3D.h"
#include "io/BoundArgs.h"
#include "io/Degrees.h"
#include "io/DerivedModules.h"
#include "io/FacetedPrimitives.h"
#include "io/Shapes2D.h"
#include "primitives/base/Tolerances.h"

namespace io {

namespace {

using csg::Vec2;
using csg::Vec3;

// The points of a curved outline segment as OpenSCAD would facet it: a circle of radius r in
// fragments(r) equal steps from its start (a whole circle() is circleVertices' polygon), an
// ellipse by its larger axis, a Bezier by chords.
void facetSegment(const csg::Segment2& s, const FragmentSettings& settings, double tolerance,
                  std::vector<Vec2>& out) {
    if (s.kind != csg::Segment2::Kind::Arc) {
        csg::appendChordPoints(s, tolerance, out);
        return;
    }
    const double r = std::max(glm::length(s.p[2]), glm::length(s.p[3]));
    const double sweep = s.th1 - s.th0;
    const int64_t n = fragments(r, settings);
    const int64_t steps =
        std::clamp<int64_t>(int64_t(std::ceil(double(n) * sweep / (2.0 * csg::kPi) - 1e-9)), 1, n);
    for (int64_t k = 0; k < steps; ++k) out.push_back(s.at(double(k) / double(steps)));
    if (sweep < 2.0 * csg::kPi) out.push_back(s.finish());
}

}  // namespace

bool facetedLeafPoints(const csg::Primitive& p, const FragmentSettings& settings,
                       std::vector<Vec3>& out) {
    if (csg::polyhedralLeafPoints(p, out)) return true;
    // A half-space has no vertices; in an intersection (a faceted rotate_extrude's wedge) its
    // plane still makes corners (csg/derived/Hull3D.h).
    if (std::holds_alternative<csg::HalfSpace>(p)) return true;
    if (const auto* sphere = std::get_if<csg::Sphere>(&p)) {
        const FacetedSolid solid =
            facetedSphere(sphere->radius, fragments(sphere->radius, settings));
        out.insert(out.end(), solid.vertices.begin(), solid.vertices.end());
        return true;
    }
    if (const auto* c = std::get_if<csg::Cylinder>(&p)) {
        const FacetedSolid solid = facetedCylinder(c->r1, c->r2, 0.0, c->height,
                                                   fragments(std::max(c->r1, c->r2), settings));
        out.insert(out.end(), solid.vertices.begin(), solid.vertices.end());
        return true;
    }
    if (const auto* t = std::get_if<csg::Torus>(&p)) {
        // A circle of radius r revolved: fragments(R + r) sections of fragments(r) points.
        const std::vector<Vec2> tube =
            circleVertices(t->minorRadius, fragments(t->minorRadius, settings));
        const int64_t sections = fragments(t->majorRadius + t->minorRadius, settings);
        for (int64_t j = 0; j < sections; ++j) {
            const double a = 360.0 * double(j) / double(sections);
            for (const Vec2& q : tube) {
                const double rho = t->majorRadius + q.x;
                out.push_back({rho * openscadCosDegrees(a), rho * openscadSinDegrees(a), q.y});
            }
        }
        return true;
    }
    const auto* e = std::get_if<csg::Extrusion>(&p);
    // A twisted side bulges past the hull of its sections' corners: no finite point set spans
    // the exact solid's hull (OpenSCAD hulls its slices instead, which csgray does not build).
    if (!e || !e->outline || e->kind == csg::Extrusion::Kind::Plane || e->twist != 0.0)
        return false;
    std::vector<Vec2> profile;
    const double tolerance =
        csg::tol::kFlattenRel * std::max(1.0, glm::length(e->box.hi - e->box.lo));
    for (const csg::Segment2& s : e->outline->segments) {
        facetSegment(s, settings, tolerance, profile);
        profile.push_back(s.finish());
    }
    if (e->kind == csg::Extrusion::Kind::Linear) {
        for (const Vec2& q : profile) {
            out.push_back({q, e->z0});
            out.push_back({q * e->scale, e->z1});
        }
        return true;
    }
    // Revolved: the profile's points (x >= 0) on fragments(max x) meridians of the sweep.
    double reach = 0.0;
    for (const Vec2& q : profile) reach = std::max(reach, q.x);
    const int64_t n = fragments(reach, settings);
    const int64_t sections =
        std::max<int64_t>(int64_t(std::ceil(double(n) * e->angle / 360.0 - 1e-9)), 1);
    for (int64_t j = 0; j <= sections; ++j) {
        const double a = e->angle * double(j) / double(sections);
        for (const Vec2& q : profile)
            if (q.x >= 0.0)
                out.push_back({q.x * openscadCosDegrees(a), q.x * openscadSinDegrees(a), q.y});
    }
    return true;
}

namespace {

Instance hull2D(Evaluator& e, const InstantiationStmt& s, const csg::NodePtr& shape,
                const csg::Tags& tags) {
    csg::HullSites sites;
    csg::addHullSites(*shape, sites);
    e.spend(s.loc, sites.points.size() + sites.arcs.size());
    csg::Outline outline = csg::convexHull2D(sites);
    if (outline.segments.empty()) return csg::NodePtr();
    return csg::leaf(
        csg::Extrusion::plane(std::make_shared<csg::Outline>(std::move(outline)), "hull"), tags);
}

Instance hull3D(Evaluator& e, const InstantiationStmt& s, const csg::NodePtr& solid,
                const FragmentSettings& settings, const csg::Tags& tags) {
    const char* missing = nullptr;
    const csg::HullPoints points =
        csg::hullPointsOf(*solid, [&](const csg::Primitive& p, std::vector<Vec3>& out) {
            if (facetedLeafPoints(p, settings, out)) return true;
            if (!missing) missing = csg::primitiveName(p);
            return false;
        });
    if (missing)
        e.fail(s.loc, std::string("hull(): a ") + missing +
                          " has no vertices to hull (hull() takes OpenSCAD's solids, "
                          "polyhedra, imports and extrusions)");
    e.spend(s.loc, points.points.size());
    if (points.tooManyPlanes)
        e.warn(s.loc,
               "hull(): an intersection or difference among the children has too many "
               "faces to find all its corners; the hull may be a little too small");
    std::string why;
    std::optional<csg::ConvexPolytope> hull = csg::convexHull3D(points.points, why);
    if (!hull) {
        e.warn(s.loc, "hull(): " + why + "; the hull is empty");
        return csg::NodePtr();
    }
    return csg::leaf(std::move(*hull), tags);
}

}  // namespace

Instance hullModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {}, "hull() { ... }");
    const FragmentSettings settings = unclampedFragmentSettings(e, b, ctx);
    const csg::Tags tags{e.sourceTag(s.loc, e.childPath(state, s.name)), state.material};
    Instance children;
    {
        Evaluator::HullChildren scope(e);
        children = childrenGroup(e, b, ctx, state);
    }
    if (!children || !*children) return children;
    if (dimensionOf(*children) == 2) return hull2D(e, s, *children, tags);
    return hull3D(e, s, *children, settings, tags);
}

}  // namespace io
