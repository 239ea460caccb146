// minkowski() of solids (../shared/OPENSCAD.md section 6): the children folded left to right,
// empty ones skipped, one child itself. Each pair is summed by csg/derived/Minkowski3D.h:
//   - with an exact ball (sphere() whose curve mode keeps it exact, under a transform that
//     keeps it round): the exact rounded solid, the other operand's curves faceted;
//   - otherwise each operand, its curves faceted as OpenSCAD facets them, is split into convex
//     pieces (a union's operands, a convex leaf, an intersection of convex leaves) and, for a
//     part that is none of these (a difference, a polyhedron, a concave extrusion), its exact
//     boundary (csg/mesh/PolyhedralBoundary.h). Every pair of convex pieces gives the hull of
//     their vertices' sums, as OpenSCAD's; a non-convex part P and a convex piece K give
//     (P + k) ∪ one hull per boundary triangle, which needs no convex decomposition; two
//     non-convex parts P and Q give their translates by a vertex of each other's boundary
//     sheets ∪ one hull per pair of boundary triangles.
// Curves that are still exact (curve mode auto without $fn) are faceted with minkowski()'s own
// $fn, $fa, $fs, as hull() facets them.
// Of 2-D shapes: with an exact circle (circle() the curve mode keeps exact, under a transform
// that keeps it round) the exact offset of the other shape by its radius (lines and arcs,
// io/Offset.cpp), moved by its centre; otherwise OpenSCAD's Clipper sum of the polygons
// (csg/derived/Clipper2D.h), on its 2^-16 grid.
#include <array>
#include <cmath>

#include "csg/Scene.h"
#include "csg/derived/Clipper2D.h"
#include "csg/derived/Hull3D.h"
#include "csg/derived/Minkowski3D.h"
#include "csg/mesh/PolyhedralBoundary.h"
#include "io/BoundArgs.h"
#include "io/DerivedModules.h"
#include "io/FacetedPrimitives.h"
#include "io/Shapes2D.h"

namespace io {
namespace {

using csg::Mat4;
using csg::NodePtr;
using csg::Vec3;

// The common length of axes that are pairwise orthogonal and equally long, to
// tol::kBallTransformRel: the scale of a map that keeps a ball (a disc) round; else nothing.
template <class V, size_t N>
std::optional<double> roundScale(const std::array<V, N>& axes) {
    const double scale = glm::length(axes[0]);
    for (size_t i = 0; i < N; ++i) {
        if (std::abs(glm::length(axes[i]) - scale) > csg::tol::kBallTransformRel * scale)
            return std::nullopt;
        for (size_t j = i + 1; j < N; ++j)
            if (std::abs(glm::dot(axes[i], axes[j])) > csg::tol::kBallTransformRel * scale * scale)
                return std::nullopt;
    }
    return scale;
}

struct Ball {
    Vec3 center;
    double radius;
};

// The node as a ball in its parent's frame: an exact sphere under a rotation, uniform scale
// and translation.
std::optional<Ball> ballOf(const csg::Node& node) {
    const auto* sphere = std::get_if<csg::Sphere>(&node.primitive);
    if (node.op != csg::Op::Leaf || !sphere) return std::nullopt;
    const Mat4& m = node.parentFromNode;
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) return std::nullopt;
    const std::optional<double> scale =
        roundScale(std::array<Vec3, 3>{Vec3(m[0]), Vec3(m[1]), Vec3(m[2])});
    if (!scale) return std::nullopt;
    return Ball{Vec3(m[3]), sphere->radius * *scale};
}

struct Disc {
    csg::Vec2 center;
    double radius;
};

// The node as a disc in its parent's frame: a leaf whose outline is one whole circle, under
// a rotation, uniform scale and translation of the plane.
std::optional<Disc> discOf(const csg::Node& node) {
    const auto* x = std::get_if<csg::Extrusion>(&node.primitive);
    if (node.op != csg::Op::Leaf || !x || x->kind != csg::Extrusion::Kind::Plane || !x->outline ||
        x->outline->segments.size() != 1)
        return std::nullopt;
    const csg::Segment2& arc = x->outline->segments.front();
    if (arc.kind != csg::Segment2::Kind::Arc || arc.th1 - arc.th0 < 2.0 * csg::kPi)
        return std::nullopt;
    const Mat4& m = node.parentFromNode;
    const csg::Vec2 mx(m[0][0], m[0][1]), my(m[1][0], m[1][1]);
    const std::optional<double> r = roundScale(std::array<csg::Vec2, 2>{arc.p[2], arc.p[3]});
    const std::optional<double> scale = roundScale(std::array<csg::Vec2, 2>{mx, my});
    if (!r || !scale) return std::nullopt;
    const csg::Vec2 c = arc.p[1];
    return Disc{mx * c.x + my * c.y + csg::Vec2(m[3][0], m[3][1]), *r * *scale};
}

// a ⊕ b of 2-D shapes (see the head of this file).
NodePtr sum2D(Evaluator& e, const InstantiationStmt& s, const NodePtr& a, const NodePtr& b,
              const csg::Tags& tags) {
    const std::optional<Disc> discA = discOf(*a), discB = discOf(*b);
    if (discA && discB) {
        csg::Outline circle;
        const double r = discA->radius + discB->radius;
        circle.segments.push_back(csg::Segment2::circle(discA->center + discB->center, r));
        return csg::leaf(
            csg::Extrusion::plane(std::make_shared<csg::Outline>(std::move(circle)), "minkowski"),
            tags);
    }
    if (discA || discB) {
        const Disc& disc = discB ? *discB : *discA;
        const NodePtr grown =
            exactOffset(e, s.loc, discB ? a : b, disc.radius, csg::OffsetJoin::Round, tags);
        return csg::transformed(glm::translate(Mat4(1.0), Vec3(disc.center, 0.0)), grown);
    }
    std::string error;
    std::optional<csg::Outline> outline = csg::clipperMinkowski(*a, *b, error);
    if (!outline) e.fail(s.loc, "minkowski(): " + error);
    e.spend(s.loc, outline->segments.size());
    if (outline->segments.empty()) return NodePtr();
    return csg::leaf(
        csg::Extrusion::plane(std::make_shared<csg::Outline>(std::move(*outline)), "minkowski"),
        tags);
}

class Summer {
public:
    Summer(Evaluator& e, const InstantiationStmt& s, const FragmentSettings& settings,
           const csg::Tags& tags)
        : e_(e), s_(s), settings_(settings), tags_(tags) {}

    // a ⊕ b; an operand that turns out empty (a difference that leaves nothing) is skipped,
    // as OpenSCAD skips empty children.
    NodePtr sum(const NodePtr& a, const NodePtr& b) {
        const std::optional<Ball> ballA = ballOf(*a), ballB = ballOf(*b);
        if (ballA && ballB)
            return csg::transformed(glm::translate(Mat4(1.0), ballA->center + ballB->center),
                                    csg::leaf(csg::Sphere{ballA->radius + ballB->radius}, tags_));
        if (ballB) return withBall(a, b, *ballB);
        if (ballA) return withBall(b, a, *ballA);

        Operand opA, opB;
        split(a, Mat4(1.0), opA);
        split(b, Mat4(1.0), opB);
        if (opA.empty()) return b;
        if (opB.empty()) return a;
        std::vector<NodePtr> parts;
        for (const auto& pa : opA.pieces)
            for (const auto& pb : opB.pieces) {
                e_.spend(s_.loc, pa.size() * pb.size());
                std::string why;
                if (std::optional<csg::ConvexPolytope> hull = csg::hullOfSums(pa, pb, why))
                    parts.push_back(csg::leaf(std::move(*hull), tags_));
            }
        sumGeneral(opA, opB, parts);
        sumGeneral(opB, opA, parts);
        sumGeneralPairs(opA, opB, parts);
        return csg::uniteAll(parts, tags_);
    }

private:
    // An operand split into convex pieces (their vertices, in the operand's frame) and
    // subtrees that are not (each under the transforms above it).
    struct General {
        NodePtr solid;  // curves faceted
        csg::TriangleMesh boundary;
    };
    struct Operand {
        std::vector<std::vector<Vec3>> pieces;
        std::vector<General> general;  // each with a boundary: empty parts are left out
        bool empty() const { return pieces.empty() && general.empty(); }
    };

    // A straight linear_extrude (no twist, one scale for x and y: a frustum of a pyramid over
    // its section) of a single loop that turns one way is convex.
    static bool convexExtrusion(const csg::Extrusion& x) {
        if (x.kind != csg::Extrusion::Kind::Linear || x.twist != 0.0 || x.scale.x != x.scale.y ||
            !x.outline || x.outline->segments.empty())
            return false;
        const std::vector<csg::Segment2>& segments = x.outline->segments;
        std::vector<csg::Vec2> loop;
        for (size_t i = 0; i < segments.size(); ++i) {
            const csg::Segment2& g = segments[i];
            if (g.kind == csg::Segment2::Kind::Cubic || g.kind == csg::Segment2::Kind::Quadratic)
                return false;
            if (g.finish() != segments[(i + 1) % segments.size()].start()) return false;  // loops
            const int samples = g.kind == csg::Segment2::Kind::Arc ? 8 : 1;
            for (int k = 0; k < samples; ++k) loop.push_back(g.at(double(k) / samples));
        }
        double turning = 0.0;
        int sign = 0;
        for (size_t i = 0; i < loop.size(); ++i) {
            const csg::Vec2 a = loop[(i + 1) % loop.size()] - loop[i];
            const csg::Vec2 b = loop[(i + 2) % loop.size()] - loop[(i + 1) % loop.size()];
            const double cross = a.x * b.y - a.y * b.x;
            const int s = cross > 0.0 ? 1 : cross < 0.0 ? -1 : 0;
            if (s != 0 && sign != 0 && s != sign) return false;
            if (s != 0) sign = s;
            turning += std::atan2(cross, glm::dot(a, b));
        }
        return std::abs(std::abs(turning) - 2.0 * csg::kPi) < 1e-6;  // once around, not a star
    }

    // A closed mesh every one of whose triangles' planes has all the vertices on one side is
    // convex (BOSL2's spheroids, polyhedron() wedges). Meshes too big to check in a moment are
    // taken as they come: as non-convex, which is right for every solid, only slower.
    static bool convexMesh(const csg::Polyhedron& mesh) {
        if (mesh.invalidReason() || !mesh.edges().manifold()) return false;
        const csg::PolyhedronData& d = *mesh.data;
        if (double(d.triangles.size()) * double(d.vertices.size()) > 4e6) return false;
        const double slack = csg::tol::kMinkowskiConvexRel * glm::length(d.box.hi - d.box.lo);
        for (const auto& t : d.triangles) {
            const Vec3 a = d.vertices[t[0]];
            const Vec3 n = glm::cross(d.vertices[t[1]] - a, d.vertices[t[2]] - a);
            const double length = glm::length(n);
            if (!(length > 0.0)) continue;
            bool above = false, below = false;
            for (const Vec3& v : d.vertices) {
                const double h = glm::dot(n, v - a) / length;
                above |= h > slack;
                below |= h < -slack;
            }
            if (above && below) return false;
        }
        return true;
    }

    // Whether a leaf is a bounded convex solid.
    static bool convexLeaf(const csg::Primitive& p) {
        return std::visit(
            [](const auto& q) {
                using T = std::decay_t<decltype(q)>;
                if constexpr (std::is_same_v<T, csg::HalfSpace>)
                    return false;  // no vertices: unbounded
                else if constexpr (std::is_same_v<T, csg::Extrusion>)
                    return convexExtrusion(q);
                else if constexpr (std::is_same_v<T, csg::Polyhedron>)
                    return convexMesh(q);
                else if constexpr (csg::HasConvexSolid<T>)
                    return true;
                else
                    return false;
            },
            p);
    }

    // Whether every leaf under node is convex and the node is no difference: then it is an
    // intersection of convex solids (a union is split before).
    static bool intersectionOfConvex(const csg::Node& node) {
        if (node.op == csg::Op::Leaf) return convexLeaf(node.primitive);
        if (node.op != csg::Op::Intersection) return false;
        return (!node.left || intersectionOfConvex(*node.left)) &&
               (!node.right || intersectionOfConvex(*node.right));
    }

    void split(const NodePtr& node, const Mat4& parent, Operand& out) {
        if (node->op == csg::Op::Union) {
            const Mat4 frame = parent * node->parentFromNode;
            if (node->left) split(node->left, frame, out);
            if (node->right) split(node->right, frame, out);
            return;
        }
        if (intersectionOfConvex(*node)) {
            const csg::HullPoints points =
                csg::hullPointsOf(*node, [&](const csg::Primitive& p, std::vector<Vec3>& o) {
                    return facetedLeafPoints(p, settings_, o);
                });
            if (points.points.size() >= 4) {
                std::vector<Vec3> piece;
                piece.reserve(points.points.size());
                for (const Vec3& p : points.points) piece.push_back(csg::transformPoint(parent, p));
                e_.spend(s_.loc, piece.size());
                out.pieces.push_back(std::move(piece));
                return;
            }
        }
        const NodePtr solid = csg::transformed(parent, facetedTree(node));
        csg::TriangleMesh boundary = boundaryOf(solid);
        if (!boundary.empty()) out.general.push_back({solid, std::move(boundary)});
    }

    // The tree with its exact spheres and cylinders faceted as OpenSCAD facets them, so that
    // its boundary is a polyhedron.
    NodePtr facetedTree(const NodePtr& node) {
        if (node->op != csg::Op::Leaf) {
            NodePtr left = node->left ? facetedTree(node->left) : nullptr;
            NodePtr right = node->right ? facetedTree(node->right) : nullptr;
            if (left == node->left && right == node->right) return node;
            auto copy = std::make_shared<csg::Node>(*node);
            copy->left = std::move(left);
            copy->right = std::move(right);
            return copy;
        }
        std::optional<FacetedSolid> solid;
        if (const auto* sphere = std::get_if<csg::Sphere>(&node->primitive)) {
            const int64_t n = fragments(sphere->radius, settings_);
            e_.spend(s_.loc, facetedSphereFaceCount(n));
            solid = facetedSphere(sphere->radius, n);
        } else if (const auto* c = std::get_if<csg::Cylinder>(&node->primitive)) {
            const int64_t n = fragments(std::max(c->r1, c->r2), settings_);
            e_.spend(s_.loc, facetedCylinderFaceCount(n, c->r1, c->r2));
            solid = facetedCylinder(c->r1, c->r2, 0.0, c->height, n);
        }
        if (!solid) return node;
        auto copy = std::make_shared<csg::Node>(*node);
        copy->primitive = polytopeOf(std::move(*solid));
        return copy;
    }

    // The exact boundary of a polyhedral solid, or an error at the call.
    csg::TriangleMesh boundaryOf(const NodePtr& solid) {
        std::optional<csg::TriangleMesh> mesh;
        csg::PolyhedralBoundaryStats stats;
        try {
            const csg::Scene scene = csg::Scene::compile(solid);
            mesh = csg::polyhedralBoundary(scene, 0, &stats);
        } catch (const std::exception& error) {
            e_.fail(s_.loc, std::string("minkowski(): ") + error.what());
        }
        if (!mesh)
            e_.fail(s_.loc, std::string("minkowski(): csgray cannot find the boundary of an "
                                        "operand (") +
                                (stats.declined ? stats.declined : "no reason given") + ")");
        e_.spend(s_.loc, mesh->triangles.size());
        return std::move(*mesh);
    }

    // The non-convex parts of one operand summed with every convex piece of the other.
    void sumGeneral(const Operand& general, const Operand& convex, std::vector<NodePtr>& parts) {
        for (const auto& [solid, boundary] : general.general) {
            for (const auto& piece : convex.pieces) {
                e_.spend(s_.loc, boundary.triangles.size() * piece.size());
                parts.push_back(csg::transformed(glm::translate(Mat4(1.0), piece.front()), solid));
                std::vector<NodePtr> hulls = csg::sumsOfBoundaryWithConvex(boundary, piece, tags_);
                parts.insert(parts.end(), hulls.begin(), hulls.end());
            }
        }
    }

    // The non-convex parts of one operand summed with those of the other (Minkowski3D.h: the
    // translates by a vertex of each boundary sheet, and a hull per pair of triangles).
    void sumGeneralPairs(const Operand& a, const Operand& b, std::vector<NodePtr>& parts) {
        for (const General& p : a.general)
            for (const General& q : b.general) {
                const uint64_t pairs =
                    uint64_t(p.boundary.triangles.size()) * q.boundary.triangles.size();
                if (pairs > kMaxTrianglePairs)
                    e_.fail(s_.loc, "minkowski(): two non-convex operands whose boundaries have " +
                                        std::to_string(p.boundary.triangles.size()) + " and " +
                                        std::to_string(q.boundary.triangles.size()) +
                                        " triangles make " + std::to_string(pairs) +
                                        " pairs to sum; csgray sums at most " +
                                        std::to_string(kMaxTrianglePairs) +
                                        " (expected coarser operands, or a convex one)");
                // A hull of 9 points and its leaf for each pair.
                e_.spend(s_.loc, 16 * pairs);
                const auto translates = [&](const General& solid, const General& by) {
                    for (const Vec3& v : csg::sheetVertices(by.boundary))
                        parts.push_back(
                            csg::transformed(glm::translate(Mat4(1.0), v), solid.solid));
                };
                translates(p, q);
                translates(q, p);
                std::vector<NodePtr> hulls = csg::sumsOfBoundaries(p.boundary, q.boundary, tags_);
                parts.insert(parts.end(), hulls.begin(), hulls.end());
            }
    }

    // The most pairs of boundary triangles two non-convex operands may make: each becomes a
    // convex polytope leaf of ~1 KB, so 2^20 pairs take about a gigabyte.
    static constexpr uint64_t kMaxTrianglePairs = uint64_t(1) << 20;

    // solid ⊕ the ball (ballNode); the ball alone when solid is empty.
    NodePtr withBall(const NodePtr& solid, const NodePtr& ballNode, const Ball& ball) {
        const NodePtr faceted = facetedTree(solid);
        const csg::TriangleMesh boundary = boundaryOf(faceted);
        if (boundary.empty()) return ballNode;
        e_.spend(s_.loc, 4 * boundary.triangles.size());
        std::vector<NodePtr> parts =
            csg::sumsOfBoundaryWithBall(boundary, ball.center, ball.radius, tags_);
        parts.push_back(csg::transformed(glm::translate(Mat4(1.0), ball.center), faceted));
        return csg::uniteAll(parts, tags_);
    }

    Evaluator& e_;
    const InstantiationStmt& s_;
    const FragmentSettings& settings_;
    csg::Tags tags_;
};

}  // namespace

Instance minkowskiModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                         const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"convexity"}, "minkowski(convexity = 1) { ... }");
    const FragmentSettings settings = unclampedFragmentSettings(e, b, ctx);
    GeomState inner = state;
    inner.modulePath = e.childPath(state, s.name);
    bool any = false;
    std::vector<NodePtr> parts = e.instantiateChildren(s, ctx, inner, b.all, any);
    if (!any) return std::nullopt;
    const csg::Tags tags{e.sourceTag(s.loc, inner.modulePath), state.material};
    e.keepOneDimension(parts, tags.source);
    std::erase(parts, nullptr);  // empty children are skipped, as OpenSCAD skips them
    if (parts.empty()) return NodePtr();
    if (parts.size() == 1) return parts.front();
    if (dimensionOf(parts.front()) == 2) {
        NodePtr result = parts.front();
        for (size_t i = 1; i < parts.size() && result; ++i)
            result = sum2D(e, s, result, parts[i], tags);
        return result;
    }
    Summer summer(e, s, settings, tags);
    NodePtr result = parts.front();
    for (size_t i = 1; i < parts.size() && result; ++i) result = summer.sum(result, parts[i]);
    return result;
}

}  // namespace io
