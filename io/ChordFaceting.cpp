#include "io/ChordFaceting.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "csg/derived/Flatten2D.h"
#include "csg/mesh/PolyhedralBoundary.h"
#include "csg/mesh/Qef.h"
#include "io/ExtrusionMesh.h"
#include "io/FacetedPrimitives.h"
#include "io/Faceting.h"
#include "primitives/ConvexPolytope.h"

namespace io {

namespace {

// The largest singular value of m's linear part, how far it can stretch a curve: the square
// root of the largest eigenvalue of A^T A (csg/mesh/Qef.h's Jacobi decomposition).
double largestScale(const csg::Mat4& m) {
    const csg::Mat3 a(m);
    csg::Vec3 w;
    csg::Mat3 r;
    csg::symmetricEigen(glm::transpose(a) * a, w, r);
    return std::sqrt(std::max({w.x, w.y, w.z, 0.0}));
}

// Fragments for a circle of world radius r whose chords may stand `sagitta` off it: the least
// n >= 3 with r (1 - cos(pi / n)) <= sagitta (csg::chordSteps over a turn); 0 when that is more
// than `most` (below chordSteps' own cap).
int64_t fragmentsFor(double r, double sagitta, int64_t most) {
    const int64_t n = csg::chordSteps(r, 2.0 * std::numbers::pi, sagitta);
    if (n > most) return 0;
    return std::max<int64_t>(3, n);
}

// The faceted sphere, cylinder or extrusion (without the node's transform), or nullptr
// for any other leaf.
csg::NodePtr facetLeaf(const csg::Node& node, const csg::Mat4& world, double deviation) {
    const csg::Primitive& p = node.primitive;
    const double scale = largestScale(world);
    constexpr int64_t kMost = 1 << 15;
    if (const auto* sphere = std::get_if<csg::Sphere>(&p)) {
        // A face between two rings stands off the sphere by about the sagitta across the rings
        // plus the one along them: half the deviation each.
        const int64_t n = fragmentsFor(sphere->radius * scale, 0.5 * deviation, kMost);
        if (n == 0 || facetedSphereFaceCount(n) >= csg::ConvexPolytope::kMaxPlanes) return nullptr;
        return csg::leaf(polytopeOf(facetedSphere(sphere->radius, n),
                                    {"sphere", uint32_t(n), uint32_t(sphereRingCount(n))}),
                         node.tags);
    }
    if (const auto* cylinder = std::get_if<csg::Cylinder>(&p)) {
        const double r = std::max(cylinder->r1, cylinder->r2);
        const int64_t n = fragmentsFor(r * scale, deviation, kMost);
        if (n == 0 || facetedCylinderFaceCount(n, cylinder->r1, cylinder->r2) >=
                          csg::ConvexPolytope::kMaxPlanes)
            return nullptr;
        return csg::leaf(
            polytopeOf(facetedCylinder(cylinder->r1, cylinder->r2, 0.0, cylinder->height, n),
                       {"cylinder", uint32_t(n), 0}),
            node.tags);
    }
    if (const auto* extrusion = std::get_if<csg::Extrusion>(&p)) {
        std::optional<csg::Polyhedron> mesh = extrusionMesh(*extrusion, deviation / scale);
        if (!mesh) return nullptr;
        return csg::leaf(std::move(*mesh), node.tags);
    }
    return nullptr;
}

csg::NodePtr facet(const csg::NodePtr& node, const csg::Mat4& parent, double deviation,
                   bool& curvedLeft) {
    if (!node || curvedLeft) return node;
    const csg::Mat4 world = parent * node->parentFromNode;
    if (node->op == csg::Op::Leaf) {
        if (csg::polyhedralLeaf(node->primitive)) return node;
        csg::NodePtr leaf = facetLeaf(*node, world, deviation);
        if (!leaf) {
            curvedLeft = true;
            return nullptr;
        }
        auto placed = std::make_shared<csg::Node>(*leaf);
        placed->parentFromNode = node->parentFromNode;
        return placed;
    }
    auto copy = std::make_shared<csg::Node>(*node);
    copy->left = facet(node->left, world, deviation, curvedLeft);
    copy->right = facet(node->right, world, deviation, curvedLeft);
    return copy;
}

}  // namespace

csg::NodePtr facetToDeviation(const csg::NodePtr& root, double deviation) {
    bool curvedLeft = false;
    csg::NodePtr out = facet(root, csg::Mat4(1.0), deviation, curvedLeft);
    return curvedLeft ? nullptr : out;
}

std::function<std::optional<csg::Scene>(double deviation)> curveFaceter(csg::NodePtr root) {
    return [root = std::move(root)](double deviation) -> std::optional<csg::Scene> {
        const csg::NodePtr faceted = facetToDeviation(root, deviation);
        if (!faceted) return std::nullopt;
        return csg::Scene::compile(faceted);
    };
}

}  // namespace io
