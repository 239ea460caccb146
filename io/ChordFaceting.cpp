#include "io/ChordFaceting.h"

#include <algorithm>
#include <cmath>
#include <map>
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

// The largest and smallest singular values of m's linear part, how far it can stretch and
// shrink a curve: square roots of the extreme eigenvalues of A^T A (csg/mesh/Qef.h's Jacobi
// decomposition).
struct Stretch {
    double largest, smallest;
};
Stretch stretchOf(const csg::Mat4& m) {
    const csg::Mat3 a(m);
    csg::Vec3 w;
    csg::Mat3 r;
    csg::symmetricEigen(glm::transpose(a) * a, w, r);
    return {std::sqrt(std::max({w.x, w.y, w.z, 0.0})),
            std::sqrt(std::max(std::min({w.x, w.y, w.z}), 0.0))};
}

// Fragments for a circle of world radius r whose chords may stand `sagitta` off it: the least
// n >= 3 with r (1 - cos(pi / n)) <= sagitta (csg::chordSteps over a turn); 0 when that is more
// than `most` (below chordSteps' own cap).
int64_t fragmentsFor(double r, double sagitta, int64_t most) {
    const int64_t n = csg::chordSteps(r, 2.0 * std::numbers::pi, sagitta);
    if (n > most) return 0;
    return std::max<int64_t>(3, n);
}

// A polytope inscribed in a curve of radius r has its vertices on the curve and its faces up to
// r (1 - c) inside it (c r: the distance of its nearest face plane from the centre or axis).
// Balanced, it is scaled by 2 / (1 + c) about that centre or axis: its vertices stand
// r (1 - c) / (1 + c) outside and its nearest faces as far inside, and every point between (the
// polytope is convex and star-shaped about the centre). Returns the scale for the fit, or 0
// when the faces would stand more than `deviation` off a curve of world radius r.
double fitScale(csg::FacetFit fit, double c, double r, double deviation) {
    if (fit == csg::FacetFit::Inscribed) return r * (1.0 - c) <= deviation ? 1.0 : 0.0;
    return r * (1.0 - c) / (1.0 + c) <= deviation ? 2.0 / (1.0 + c) : 0.0;
}

// Where a search for the fewest fragments that fit may start: below the chord rule at the
// deviation (inscribed) or twice it (balanced), an equator face alone stands too far off, since
// c <= cos(pi / n) and 1 + c <= 2.
int64_t leastFragmentsToTry(csg::FacetFit fit, double r, double deviation, int64_t most) {
    return fragmentsFor(r, fit == csg::FacetFit::Balanced ? 2.0 * deviation : deviation, most);
}

// The fewest fragments n, counting up from leastFragmentsToTry, whose fit stands within the
// deviation (nearest(n): the nearest face's c), with the fit's scale; nothing when faces(n)
// reaches what a polytope may have first, or n passes `most`.
struct Fragments {
    int64_t n;
    double scale;
};
template <class FaceCount, class Nearest>
std::optional<Fragments> fewestFragments(csg::FacetFit fit, double r, double deviation,
                                         int64_t most, FaceCount faces, Nearest nearest) {
    for (int64_t n = leastFragmentsToTry(fit, r, deviation, most); n != 0 && n <= most; ++n) {
        if (faces(n) >= csg::ConvexPolytope::kMaxPlanes) return std::nullopt;
        if (const double f = fitScale(fit, nearest(n), r, deviation); f > 0.0)
            return Fragments{n, f};
    }
    return std::nullopt;
}

// c of facetedSphere(1, n): its nearest face plane's distance from the centre. In the meridian
// plane through a side face's middle, the face's edges on rings i and i + 1 are the points
// (cos(pi / n) sin(phi), cos(phi)) at the rings' polar angles, and its plane is the line through
// them; the caps stand cos(phi_0) off.
double nearestSphereFace(int64_t n) {
    const int64_t rings = sphereRingCount(n);
    const double edge = std::cos(std::numbers::pi / double(n));
    auto polar = [rings](int64_t i) {
        return std::numbers::pi * (double(i) + 0.5) / double(rings);
    };
    double c = std::cos(polar(0));
    for (int64_t i = 0; i + 1 < rings; ++i) {
        const double a1 = edge * std::sin(polar(i)), b1 = std::cos(polar(i));
        const double a2 = edge * std::sin(polar(i + 1)), b2 = std::cos(polar(i + 1));
        c = std::min(c, std::abs(a1 * b2 - a2 * b1) / std::hypot(a1 - a2, b1 - b2));
    }
    return c;
}

// A sphere and a straight cylinder of the same world radius (a rounded box's corner and edge, a
// capsule) are most often tangent along a circle: faceted with one layout, their vertices meet
// on it and the boundary there is a clean seam, where two layouts cut each other into slivers
// (Debian's example022: 776 triangles with one layout of 14 fragments, 1 144 with 14 and 10).
// The shared layout has the fragments that both need, rounded up to 2 modulo 4, where the
// sphere has a ring on its equator (sphereRingCount odd), and the sphere's fit scale, which
// keeps the cylinder within the deviation too (its faces stand nearer the curve than the
// sphere's: cos(pi / n) >= the sphere's c).
struct SharedLayout {
    int64_t n = 0;
    double scale = 0.0;
};
// Keyed by the world radius (similarity transforms only), rounded to 1e-9 of it.
using RadiusKey = int64_t;
RadiusKey radiusKey(double r) {
    return std::llround(std::log(r) * 1e9);
}

struct RadiusUse {
    bool sphere = false, cylinder = false;
    int64_t n = 0;  // the most fragments any of them needs alone
};

// Radii in world units of a similarity transform's sphere or straight cylinder; 0 otherwise.
double sharableRadius(const csg::Primitive& p, const csg::Mat4& world) {
    const Stretch stretch = stretchOf(world);
    if (!(stretch.largest - stretch.smallest <= 1e-12 * stretch.largest)) return 0.0;
    if (const auto* sphere = std::get_if<csg::Sphere>(&p)) return sphere->radius * stretch.largest;
    if (const auto* cylinder = std::get_if<csg::Cylinder>(&p))
        if (cylinder->r1 == cylinder->r2) return cylinder->r1 * stretch.largest;
    return 0.0;
}

// The faceted sphere, cylinder or extrusion (without the node's transform), or nullptr
// for any other leaf. Spheres and cylinders get the fewest fragments whose fit stands within the
// deviation, checked with their faces' exact planes.
constexpr int64_t kMostFragments = 1 << 15;

std::optional<Fragments> sphereFragments(double r, double deviation, csg::FacetFit fit) {
    return fewestFragments(fit, r, deviation, kMostFragments, facetedSphereFaceCount,
                           nearestSphereFace);
}

std::optional<Fragments> cylinderFragments(const csg::Cylinder& cylinder, double scale,
                                           double deviation, csg::FacetFit fit) {
    // The sides of an n-gon's prism or frustum stand r (1 - cos(pi / n)) inside the curve at
    // each height (less across a cone's slant): c = cos(pi / n).
    return fewestFragments(
        fit, std::max(cylinder.r1, cylinder.r2) * scale, deviation, kMostFragments,
        [&](int64_t n) { return facetedCylinderFaceCount(n, cylinder.r1, cylinder.r2); },
        [](int64_t n) { return std::cos(std::numbers::pi / double(n)); });
}

// shared: the layouts of radii that a sphere and a cylinder share (see SharedLayout).
csg::NodePtr facetLeaf(const csg::Node& node, const csg::Mat4& world, double deviation,
                       csg::FacetFit fit, const std::map<RadiusKey, SharedLayout>& shared) {
    const csg::Primitive& p = node.primitive;
    const double scale = stretchOf(world).largest;
    std::optional<Fragments> layout;
    if (const double r = sharableRadius(p, world); r > 0.0)
        if (const auto it = shared.find(radiusKey(r)); it != shared.end())
            layout = Fragments{it->second.n, it->second.scale};
    if (const auto* sphere = std::get_if<csg::Sphere>(&p)) {
        const std::optional<Fragments> k =
            layout ? layout : sphereFragments(sphere->radius * scale, deviation, fit);
        if (!k) return nullptr;
        return csg::leaf(polytopeOf(facetedSphere(k->scale * sphere->radius, k->n),
                                    {"sphere", uint32_t(k->n), uint32_t(sphereRingCount(k->n))}),
                         node.tags);
    }
    if (const auto* cylinder = std::get_if<csg::Cylinder>(&p)) {
        const std::optional<Fragments> k =
            layout ? layout : cylinderFragments(*cylinder, scale, deviation, fit);
        if (!k) return nullptr;
        return csg::leaf(
            polytopeOf(facetedCylinder(k->scale * cylinder->r1, k->scale * cylinder->r2, 0.0,
                                       cylinder->height, k->n),
                       {"cylinder", uint32_t(k->n), 0}),
            node.tags);
    }
    if (const auto* extrusion = std::get_if<csg::Extrusion>(&p)) {
        std::optional<csg::Polyhedron> mesh = extrusionMesh(*extrusion, deviation / scale);
        if (!mesh) return nullptr;
        return csg::leaf(std::move(*mesh), node.tags);
    }
    return nullptr;
}

// Which radii a sphere and a cylinder share, and the most fragments any of them needs alone.
void collectRadii(const csg::NodePtr& node, const csg::Mat4& parent, double deviation,
                  csg::FacetFit fit, std::map<RadiusKey, RadiusUse>& uses) {
    if (!node) return;
    const csg::Mat4 world = parent * node->parentFromNode;
    if (node->op != csg::Op::Leaf) {
        collectRadii(node->left, world, deviation, fit, uses);
        collectRadii(node->right, world, deviation, fit, uses);
        return;
    }
    const double r = sharableRadius(node->primitive, world);
    if (!(r > 0.0)) return;
    RadiusUse& use = uses[radiusKey(r)];
    const bool sphere = std::holds_alternative<csg::Sphere>(node->primitive);
    const std::optional<Fragments> alone =
        sphere ? sphereFragments(r, deviation, fit)
               : cylinderFragments(csg::Cylinder{1.0, r, r}, 1.0, deviation, fit);
    (sphere ? use.sphere : use.cylinder) = true;
    use.n = std::max(use.n, alone ? alone->n : kMostFragments + 1);
}

std::map<RadiusKey, SharedLayout> sharedLayouts(const csg::NodePtr& root, double deviation,
                                                csg::FacetFit fit) {
    std::map<RadiusKey, RadiusUse> uses;
    collectRadii(root, csg::Mat4(1.0), deviation, fit, uses);
    std::map<RadiusKey, SharedLayout> shared;
    for (const auto& [key, use] : uses) {
        if (!use.sphere || !use.cylinder) continue;
        const double r = std::exp(double(key) * 1e-9);
        // The fewest n = 2 (mod 4) from use.n whose sphere fits (its nearest face need not
        // move monotonically with n).
        for (int64_t n = use.n + (6 - use.n % 4) % 4; n <= kMostFragments; n += 4) {
            if (facetedSphereFaceCount(n) >= csg::ConvexPolytope::kMaxPlanes) break;
            if (const double f = fitScale(fit, nearestSphereFace(n), r, deviation); f > 0.0) {
                shared[key] = {n, f};
                break;
            }
        }
    }
    return shared;
}

csg::NodePtr facet(const csg::NodePtr& node, const csg::Mat4& parent, double deviation,
                   csg::FacetFit fit, const std::map<RadiusKey, SharedLayout>& shared,
                   bool& curvedLeft) {
    if (!node || curvedLeft) return node;
    const csg::Mat4 world = parent * node->parentFromNode;
    if (node->op == csg::Op::Leaf) {
        if (csg::polyhedralLeaf(node->primitive)) return node;
        csg::NodePtr leaf = facetLeaf(*node, world, deviation, fit, shared);
        if (!leaf) {
            curvedLeft = true;
            return nullptr;
        }
        auto placed = std::make_shared<csg::Node>(*leaf);
        placed->parentFromNode = node->parentFromNode;
        return placed;
    }
    auto copy = std::make_shared<csg::Node>(*node);
    copy->left = facet(node->left, world, deviation, fit, shared, curvedLeft);
    copy->right = facet(node->right, world, deviation, fit, shared, curvedLeft);
    return copy;
}

}  // namespace

csg::NodePtr facetToDeviation(const csg::NodePtr& root, double deviation, csg::FacetFit fit) {
    bool curvedLeft = false;
    csg::NodePtr out = facet(root, csg::Mat4(1.0), deviation, fit,
                             sharedLayouts(root, deviation, fit), curvedLeft);
    return curvedLeft ? nullptr : out;
}

csg::CurveFaceter curveFaceter(csg::NodePtr root) {
    return
        [root = std::move(root)](double deviation, csg::FacetFit fit) -> std::optional<csg::Scene> {
            const csg::NodePtr faceted = facetToDeviation(root, deviation, fit);
            if (!faceted) return std::nullopt;
            return csg::Scene::compile(faceted);
        };
}

}  // namespace io
