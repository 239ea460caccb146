#include "io/ChordFaceting.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <vector>

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
        if (const double f = csg::facetFitScale(fit, nearest(n), r, deviation); f > 0.0)
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

// A sphere whose centre is an end centre of a straight cylinder's axis, of the same world
// radius (a rounded box's corner and edge, a capsule), is tangent to it along the end circle:
// faceted with one layout, their vertices meet there and the boundary is a clean seam, where
// two layouts cut each other into slivers (Debian's example022 at T = 0.19: 824 triangles
// with shared layouts, 1 272 with its spheres' 14 fragments and cylinders' 10). The shared
// layout has the fragments that all the leaves of that radius meeting so need, rounded up to 2
// modulo 4, where the sphere has a ring on its equator (sphereRingCount odd), and the sphere's
// fit scale, which keeps a cylinder within the deviation too (its faces stand nearer the curve
// than the sphere's: cos(pi / n) >= the sphere's c).
struct SharedLayout {
    int64_t n = 0;
    double scale = 0.0;
};

// A point where such leaves meet, keyed by the world radius and position, rounded to 1e-9 of
// the radius.
struct SeamKey {
    int64_t radius, x, y, z;
    auto operator<=>(const SeamKey&) const = default;
};

// A sphere's or straight cylinder's world radius and the points where a partner meets it (the
// sphere's centre; the cylinder's two end centres), under a similarity transform; no points
// for any other leaf.
struct SeamPoints {
    double radius = 0.0;
    bool sphere = false;
    int count = 0;
    SeamKey keys[2]{};
};
SeamPoints seamPointsOf(const csg::Primitive& p, const csg::Mat4& world, const Stretch& stretch) {
    SeamPoints out;
    if (!(stretch.largest - stretch.smallest <= 1e-12 * stretch.largest)) return out;
    csg::Vec3 ends[2];
    int count = 0;
    if (const auto* sphere = std::get_if<csg::Sphere>(&p)) {
        out.radius = sphere->radius * stretch.largest;
        out.sphere = true;
        ends[count++] = csg::Vec3(world[3]);
    } else if (const auto* cylinder = std::get_if<csg::Cylinder>(&p);
               cylinder && cylinder->r1 == cylinder->r2) {
        out.radius = cylinder->r1 * stretch.largest;
        ends[count++] = csg::Vec3(world[3]);
        ends[count++] = csg::Vec3(world * csg::Vec4(0.0, 0.0, cylinder->height, 1.0));
    }
    if (!(out.radius > 0.0) || !std::isfinite(out.radius)) return out;
    const double step = 1e-9 * out.radius;
    const int64_t radius = std::llround(std::log(out.radius) * 1e9);
    for (int i = 0; i < count; ++i) {
        const csg::Vec3 q = ends[i] / step;
        // Farther out than int64 holds (or not finite): no partner is looked for.
        if (!(std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)}) < 1e17)) return {};
        out.keys[i] = {radius, std::llround(q.x), std::llround(q.y), std::llround(q.z)};
    }
    out.count = count;
    return out;
}

struct Seams {
    std::set<SeamKey> points;                 // where a sphere and a cylinder meet
    std::map<int64_t, SharedLayout> layouts;  // by SeamKey::radius
    // The layout of a leaf that meets a partner at one of its points.
    std::optional<SharedLayout> layoutOf(const SeamPoints& leaf) const {
        for (int i = 0; i < leaf.count; ++i)
            if (points.count(leaf.keys[i])) {
                const auto it = layouts.find(leaf.keys[i].radius);
                if (it != layouts.end()) return it->second;
            }
        return std::nullopt;
    }
};

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

// The part of a convex solid where s z <= h (s = 1 or -1): each face clipped to it (a point
// where an edge crosses the plane is one vertex, shared by the edge's two faces) and the
// plane's section as a new face, counter-clockwise from outside.
io::FacetedSolid keptUnder(const io::FacetedSolid& solid, double s, double h) {
    const auto height = [&](uint32_t v) { return s * solid.vertices[v].z; };
    const uint32_t count = uint32_t(solid.vertices.size());
    bool cut = false;
    for (uint32_t v = 0; v < count; ++v) cut = cut || height(v) > h;
    if (!cut) return solid;
    constexpr uint32_t kGone = ~0u;
    io::FacetedSolid out;
    std::vector<uint32_t> kept(count, kGone);
    for (uint32_t v = 0; v < count; ++v) {
        if (height(v) > h) continue;
        kept[v] = uint32_t(out.vertices.size());
        out.vertices.push_back(solid.vertices[v]);
    }
    // The point where edge (a kept, b not) meets the plane: the kept end itself when it lies
    // on the plane, else one new vertex per edge, with z exactly on the plane.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> crossings;
    const auto crossing = [&](uint32_t a, uint32_t b) {
        if (height(a) == h) return kept[a];
        const auto [at, fresh] = crossings.try_emplace(std::minmax(a, b), 0u);
        if (fresh) {
            const csg::Vec3 &p = solid.vertices[a], &q = solid.vertices[b];
            csg::Vec3 x = p + (h - height(a)) / (height(b) - height(a)) * (q - p);
            x.z = s * h;
            at->second = uint32_t(out.vertices.size());
            out.vertices.push_back(x);
        }
        return at->second;
    };
    std::vector<uint32_t> face;
    for (size_t f = 0; f + 1 < solid.faceStarts.size(); ++f) {
        face.clear();
        const auto push = [&](uint32_t v) {
            if (face.empty() || (face.back() != v && face.front() != v)) face.push_back(v);
        };
        const uint32_t first = solid.faceStarts[f], end = solid.faceStarts[f + 1];
        for (uint32_t i = first; i < end; ++i) {
            const uint32_t a = solid.faceVertices[i];
            const uint32_t b = solid.faceVertices[i + 1 < end ? i + 1 : first];
            if (kept[a] != kGone) push(kept[a]);
            if (kept[a] != kGone && kept[b] == kGone) push(crossing(a, b));
            if (kept[a] == kGone && kept[b] != kGone) push(crossing(b, a));
        }
        if (face.size() < 3) continue;
        out.faceVertices.insert(out.faceVertices.end(), face.begin(), face.end());
        out.faceStarts.push_back(uint32_t(out.faceVertices.size()));
    }
    // The section: every vertex on the plane, by angle about their centroid, counter-clockwise
    // seen from outside (from +z for s = 1).
    std::vector<uint32_t> section;
    csg::Vec3 centre(0.0);
    for (uint32_t v = 0; v < out.vertices.size(); ++v)
        if (s * out.vertices[v].z == h) {
            section.push_back(v);
            centre += out.vertices[v];
        }
    if (section.size() < 3) return out;  // the plane only touches what is left
    centre /= double(section.size());
    const auto angle = [&](uint32_t v) {
        return s * std::atan2(out.vertices[v].y - centre.y, out.vertices[v].x - centre.x);
    };
    std::sort(section.begin(), section.end(),
              [&](uint32_t a, uint32_t b) { return angle(a) < angle(b); });
    out.faceVertices.insert(out.faceVertices.end(), section.begin(), section.end());
    out.faceStarts.push_back(uint32_t(out.faceVertices.size()));
    return out;
}

// A balanced sphere of radius r cut to the planes of its poles, z = r and z = -r: its caps
// stand above the poles (every vertex is outside the exact sphere), so a pocket cut flush with
// a pole would keep that slice as a skin. What the cut leaves stays within the deviation (it
// lies inside the balanced polytope and outside the sphere, or on it at the poles).
io::FacetedSolid balancedSphere(double r, double scale, int64_t n) {
    return keptUnder(keptUnder(io::facetedSphere(scale * r, n), 1.0, r), -1.0, r);
}

// How a leaf's surface is curved: not at all, one way only (a cylinder's sides are straight
// along its axis), or both ways.
enum class Curving { None, OneWay, BothWays };
Curving curvingOf(const csg::Primitive& p) {
    if (std::holds_alternative<csg::Sphere>(p) || std::holds_alternative<csg::Torus>(p))
        return Curving::BothWays;
    if (std::holds_alternative<csg::Cylinder>(p)) return Curving::OneWay;
    const auto* extrusion = std::get_if<csg::Extrusion>(&p);
    if (!extrusion || !extrusion->outline) return Curving::None;
    if (extrusion->twisted) return Curving::BothWays;
    const bool curvedOutline = !csg::straightEdged(*extrusion->outline);
    if (extrusion->kind == csg::Extrusion::Kind::Rotate)
        return curvedOutline ? Curving::BothWays : Curving::OneWay;
    return curvedOutline ? Curving::OneWay : Curving::None;
}
// The curvings of the tree's leaves, a bit (1 << Curving) each.
unsigned curvingsOf(const csg::NodePtr& node) {
    if (!node) return 0;
    if (node->op == csg::Op::Leaf) return 1u << unsigned(curvingOf(node->primitive));
    return curvingsOf(node->left) | curvingsOf(node->right);
}
// The faceted sphere, cylinder, extrusion or torus (without the node's transform), or nullptr
// for any other leaf. Spheres and cylinders get the fewest fragments whose fit stands within the
// deviation, checked with their faces' exact planes, or the layout they share with a leaf they
// meet at a seam (see SharedLayout).
csg::NodePtr facetLeaf(const csg::Node& node, const csg::Mat4& world, double deviation,
                       csg::FacetFit fit, double oneWayShare, const Seams& seams) {
    const csg::Primitive& p = node.primitive;
    if (curvingOf(p) == Curving::OneWay) deviation *= oneWayShare;
    const Stretch stretch = stretchOf(world);
    const double scale = stretch.largest;
    std::optional<Fragments> layout;
    if (const std::optional<SharedLayout> shared = seams.layoutOf(seamPointsOf(p, world, stretch)))
        layout = Fragments{shared->n, shared->scale};
    if (const auto* sphere = std::get_if<csg::Sphere>(&p)) {
        const std::optional<Fragments> k =
            layout ? layout : sphereFragments(sphere->radius * scale, deviation, fit);
        if (!k) return nullptr;
        const io::FacetedSolid solid = k->scale > 1.0
                                           ? balancedSphere(sphere->radius, k->scale, k->n)
                                           : facetedSphere(k->scale * sphere->radius, k->n);
        return csg::leaf(
            polytopeOf(solid, {"sphere", uint32_t(k->n), uint32_t(sphereRingCount(k->n))}),
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
        std::optional<csg::Polyhedron> mesh = extrusionMesh(*extrusion, deviation / scale, fit);
        if (!mesh) return nullptr;
        return csg::leaf(std::move(*mesh), node.tags);
    }
    if (const auto* torus = std::get_if<csg::Torus>(&p)) {
        // The revolution of its tube's circle about z, faceted as that extrusion is.
        csg::Outline tube;
        tube.segments.push_back(
            csg::Segment2::circle({torus->majorRadius, 0.0}, torus->minorRadius));
        tube.buildIndex();
        const csg::Extrusion revolution =
            csg::Extrusion::plane(std::make_shared<const csg::Outline>(std::move(tube)), "circle")
                .rotated(360.0);
        std::optional<csg::Polyhedron> mesh = extrusionMesh(revolution, deviation / scale, fit);
        if (!mesh) return nullptr;
        return csg::leaf(std::move(*mesh), node.tags);
    }
    return nullptr;
}

// Every sphere's and straight cylinder's seam points.
void collectSeamPoints(const csg::NodePtr& node, const csg::Mat4& parent,
                       std::vector<SeamPoints>& leaves) {
    if (!node) return;
    const csg::Mat4 world = parent * node->parentFromNode;
    if (node->op != csg::Op::Leaf) {
        collectSeamPoints(node->left, world, leaves);
        collectSeamPoints(node->right, world, leaves);
        return;
    }
    if (const SeamPoints points = seamPointsOf(node->primitive, world, stretchOf(world));
        points.count > 0)
        leaves.push_back(points);
}

Seams findSeams(const csg::NodePtr& root, double deviation, csg::FacetFit fit) {
    std::vector<SeamPoints> leaves;
    collectSeamPoints(root, csg::Mat4(1.0), leaves);
    // Points with a sphere (bit 1) and a cylinder (bit 2).
    std::map<SeamKey, int> kinds;
    for (const SeamPoints& leaf : leaves)
        for (int i = 0; i < leaf.count; ++i) kinds[leaf.keys[i]] |= leaf.sphere ? 1 : 2;
    Seams seams;
    for (const auto& [key, kind] : kinds)
        if (kind == 3) seams.points.insert(key);
    // The most fragments a leaf meeting a partner needs alone, by radius.
    struct Need {
        int64_t n = 0;
        double radius = 0.0;
    };
    std::map<int64_t, Need> need;  // by SeamKey::radius
    for (const SeamPoints& leaf : leaves) {
        if (!std::any_of(leaf.keys, leaf.keys + leaf.count,
                         [&](const SeamKey& k) { return seams.points.count(k) > 0; }))
            continue;
        const double r = leaf.radius;
        const std::optional<Fragments> alone =
            leaf.sphere ? sphereFragments(r, deviation, fit)
                        : cylinderFragments(csg::Cylinder{1.0, r, r}, 1.0, deviation, fit);
        Need& n = need[leaf.keys[0].radius];
        n.n = std::max(n.n, alone ? alone->n : kMostFragments + 1);
        n.radius = r;
    }
    for (const auto& [key, needed] : need) {
        // The fewest n = 2 (mod 4) from needed.n whose sphere fits (its nearest face need not
        // move monotonically with n).
        for (int64_t n = needed.n + (6 - needed.n % 4) % 4; n <= kMostFragments; n += 4) {
            if (facetedSphereFaceCount(n) >= csg::ConvexPolytope::kMaxPlanes) break;
            if (const double f =
                    csg::facetFitScale(fit, nearestSphereFace(n), needed.radius, deviation);
                f > 0.0) {
                seams.layouts[key] = {n, f};
                break;
            }
        }
    }
    return seams;
}

csg::NodePtr facet(const csg::NodePtr& node, const csg::Mat4& parent, double deviation,
                   csg::FacetFit fit, double oneWayShare, const Seams& seams, bool& curvedLeft) {
    if (!node || curvedLeft) return node;
    const csg::Mat4 world = parent * node->parentFromNode;
    if (node->op == csg::Op::Leaf) {
        if (csg::polyhedralLeaf(node->primitive)) return node;
        csg::NodePtr leaf = facetLeaf(*node, world, deviation, fit, oneWayShare, seams);
        if (!leaf) {
            curvedLeft = true;
            return nullptr;
        }
        auto placed = std::make_shared<csg::Node>(*leaf);
        placed->parentFromNode = node->parentFromNode;
        return placed;
    }
    auto copy = std::make_shared<csg::Node>(*node);
    copy->left = facet(node->left, world, deviation, fit, oneWayShare, seams, curvedLeft);
    copy->right = facet(node->right, world, deviation, fit, oneWayShare, seams, curvedLeft);
    return copy;
}

}  // namespace

csg::NodePtr facetToDeviation(const csg::NodePtr& root, double deviation, csg::FacetFit fit,
                              double oneWayShare) {
    if (oneWayShare != 1.0 && !mixedCurvature(root)) oneWayShare = 1.0;
    bool curvedLeft = false;
    csg::NodePtr out = facet(root, csg::Mat4(1.0), deviation, fit, oneWayShare,
                             findSeams(root, deviation, fit), curvedLeft);
    return curvedLeft ? nullptr : out;
}

bool mixedCurvature(const csg::NodePtr& root) {
    const unsigned curvings = curvingsOf(root);
    return (curvings >> unsigned(Curving::OneWay) & 1u) &&
           (curvings >> unsigned(Curving::BothWays) & 1u);
}

csg::CurveFaceter curveFaceter(csg::NodePtr root) {
    const bool mixed = mixedCurvature(root);
    return {[root = std::move(root)](double deviation, csg::FacetFit fit,
                                     double oneWayShare) -> std::optional<csg::Scene> {
                const csg::NodePtr faceted = facetToDeviation(root, deviation, fit, oneWayShare);
                if (!faceted) return std::nullopt;
                return csg::Scene::compile(faceted);
            },
            mixed};
}

}  // namespace io
