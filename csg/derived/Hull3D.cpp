// Notation: points and planes are in the hull's frame ("world" here); a plane is n . x = c
// with |n| = 1 (which side is inside does not matter: planes only make corners and step
// directions). scale = max(1, largest |coordinate| of the points): the tolerances are relative.
#include "csg/derived/Hull3D.h"

#include <libqhull_r/qhull_ra.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "csg/derived/Flatten2D.h"

namespace csg {

namespace {

// A point within this fraction of the scale of a plane lies on it.
constexpr double kOnPlaneRel = 1e-9;
// How far off a corner the solid is tried, relative to the scale: 100 times kOnPlaneRel, and
// ~10^7 below any feature a part draws.
constexpr double kStepRel = 1e-7;

// A face's plane, with the box of the face (infinite for a half-space's): three faces can only
// meet at a corner inside all three boxes.
struct Plane {
    Vec3 n;
    double c;
    uint32_t leaf;
    Bounds3 face;
};

struct Leaf {
    const Node* node;
    Mat4 worldFromLocal;
};

Mat4 frameOf(const Mat4& parent, const Node& node) {
    return parent * node.parentFromNode;
}

Bounds3 everywhere() {
    return {Vec3(-kInfinity), Vec3(kInfinity)};
}

// The world plane of local plane n . l = c under x = W l, with the world box of the face's
// local points (none: an unbounded face).
void worldPlane(const Mat4& w, Vec3 n, double c, uint32_t leaf, std::vector<Plane>& out,
                std::initializer_list<Vec3> face = {}, const Bounds3* faceBox = nullptr) {
    const Mat3 a(w);
    const Vec3 t(w[3]);
    const Vec3 m = glm::transpose(glm::inverse(a)) * n;
    const double len = glm::length(m);
    if (!(len > 0.0) || !std::isfinite(len)) return;
    Bounds3 box;
    for (const Vec3& p : face) box.extend(transformPoint(w, p));
    if (faceBox) {
        for (int k = 0; k < 8; ++k)
            box.extend(transformPoint(w, {(k & 1) ? faceBox->hi.x : faceBox->lo.x,
                                          (k & 2) ? faceBox->hi.y : faceBox->lo.y,
                                          (k & 4) ? faceBox->hi.z : faceBox->lo.z}));
    }
    if (face.size() == 0 && !faceBox) box = everywhere();
    out.push_back({m / len, (c + glm::dot(m, t)) / len, leaf, box});
}

// The planes of a leaf's faces (false: it has curved faces too).
bool leafPlanes(const Leaf& leaf, uint32_t id, std::vector<Plane>& out) {
    const Mat4& w = leaf.worldFromLocal;
    const Primitive& p = leaf.node->primitive;
    if (const auto* box = std::get_if<Box>(&p)) {
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 n(0.0);
            n[axis] = 1.0;
            Bounds3 face{box->lo, box->hi};
            face.lo[axis] = box->hi[axis];
            worldPlane(w, n, box->hi[axis], id, out, {}, &face);
            face = Bounds3{box->lo, box->hi};
            face.hi[axis] = box->lo[axis];
            worldPlane(w, -n, -box->lo[axis], id, out, {}, &face);
        }
        return true;
    }
    if (const auto* poly = std::get_if<ConvexPolytope>(&p)) {
        if (!poly->data) return true;
        // A face: the vertices on its plane (fromFaces pushed each plane out to its farthest
        // face vertex, so they lie on it to rounding).
        double size = 1.0;
        for (const Vec3& v : poly->data->vertices)
            size = std::max({size, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
        for (const PolytopePlane& plane : poly->data->planes) {
            Bounds3 face;
            for (const Vec3& v : poly->data->vertices)
                if (std::abs(glm::dot(plane.normal, v) - plane.offset) <= kOnPlaneRel * size)
                    face.extend(v);
            worldPlane(w, plane.normal, plane.offset, id, out, {}, face.empty() ? nullptr : &face);
        }
        return true;
    }
    if (const auto* half = std::get_if<HalfSpace>(&p)) {
        worldPlane(w, half->planeNormal, half->offset, id, out);
        return true;
    }
    if (const auto* mesh = std::get_if<Polyhedron>(&p)) {
        if (!mesh->data) return true;
        std::vector<Plane> local;
        for (const auto& tri : mesh->data->triangles) {
            const Vec3 a = mesh->data->vertices[tri[0]], b = mesh->data->vertices[tri[1]],
                       c = mesh->data->vertices[tri[2]];
            const Vec3 n = glm::cross(b - a, c - a);
            const double len = glm::length(n);
            Bounds3 face;
            for (const Vec3& v : {a, b, c}) face.extend(v);
            if (len > 0.0) local.push_back({n / len, glm::dot(n / len, a), id, face});
        }
        // Coplanar triangles make one plane.
        std::sort(local.begin(), local.end(), [](const Plane& x, const Plane& y) {
            if (x.n.x != y.n.x) return x.n.x < y.n.x;
            if (x.n.y != y.n.y) return x.n.y < y.n.y;
            if (x.n.z != y.n.z) return x.n.z < y.n.z;
            return x.c < y.c;
        });
        for (size_t k = 0; k < local.size();) {
            size_t end = k + 1;
            Bounds3 face = local[k].face;
            while (end < local.size() && glm::distance(local[end].n, local[k].n) <= 1e-12 &&
                   std::abs(local[end].c - local[k].c) <= 1e-12 * (1.0 + std::abs(local[k].c)))
                face.extend(local[end++].face);
            worldPlane(w, local[k].n, local[k].c, id, out, {}, &face);
            k = end;
        }
        return true;
    }
    if (const auto* e = std::get_if<Extrusion>(&p)) {
        if (e->kind != Extrusion::Kind::Linear || !e->outline) return false;
        const Bounds2& box = e->box;
        const Bounds3 capBottom{Vec3(box.lo, e->z0), Vec3(box.hi, e->z0)};
        const Bounds3 capTop{Vec3(box.lo * e->scale, e->z1), Vec3(box.hi * e->scale, e->z1)};
        worldPlane(w, Vec3(0, 0, 1), e->z1, id, out, {}, &capTop);
        worldPlane(w, Vec3(0, 0, -1), -e->z0, id, out, {}, &capBottom);
        // An edge's side is a plane only when its top is its bottom scaled uniformly and
        // untwisted; a scale per axis or a twist makes it a ruled surface or a helicoid.
        if (e->twist != 0.0 || e->scale.x != e->scale.y) return false;
        bool allLines = true;
        for (const Segment2& s : e->outline->segments) {
            if (s.kind != Segment2::Kind::Line) {
                allLines = false;
                continue;
            }
            const Vec3 a(s.p[0], e->z0), b(s.p[1], e->z0), top(s.p[0] * e->scale, e->z1),
                topEnd(s.p[1] * e->scale, e->z1);
            const Vec3 n = glm::cross(b - a, top - a);
            if (glm::length(n) > 0.0)
                worldPlane(w, n, glm::dot(n, a), id, out, {a, b, top, topEnd});
        }
        return allLines;
    }
    return false;
}

// The leaves of a subtree with their frames.
void gatherLeaves(const Node& node, const Mat4& parent, std::vector<Leaf>& out) {
    const Mat4 frame = frameOf(parent, node);
    if (node.op == Op::Leaf) {
        out.push_back({&node, frame});
        return;
    }
    if (node.left) gatherLeaves(*node.left, frame, out);
    if (node.right) gatherLeaves(*node.right, frame, out);
}

bool insideSolid(const Node& node, const Mat4& parent, Vec3 x) {
    const Mat4 frame = frameOf(parent, node);
    switch (node.op) {
        case Op::Leaf: {
            const Vec3 local = transformPoint(glm::inverse(frame), x);
            return std::visit([&](const auto& shape) { return shape.inside(local); },
                              node.primitive);
        }
        case Op::Union:
            return (node.left && insideSolid(*node.left, frame, x)) ||
                   (node.right && insideSolid(*node.right, frame, x));
        case Op::Intersection:
            return node.left && node.right && insideSolid(*node.left, frame, x) &&
                   insideSolid(*node.right, frame, x);
        case Op::Difference:
            return node.left && insideSolid(*node.left, frame, x) &&
                   !(node.right && insideSolid(*node.right, frame, x));
    }
    return false;
}

// The corner of three planes; false when they do not meet in one point.
bool corner(const Plane& a, const Plane& b, const Plane& c, Vec3& x) {
    const Vec3 bc = glm::cross(b.n, c.n);
    const double det = glm::dot(a.n, bc);
    if (std::abs(det) < 1e-9) return false;
    x = (bc * a.c + glm::cross(c.n, a.n) * b.c + glm::cross(a.n, b.n) * c.c) / det;
    return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
}

// The step directions that find a solid's side at a point: the 26 neighbours of a cube's
// centre and 64 spread over the sphere (a golden spiral).
const std::vector<Vec3>& stepDirections() {
    static const std::vector<Vec3> directions = [] {
        std::vector<Vec3> d;
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z)
                    if (x || y || z) d.push_back(glm::normalize(Vec3(x, y, z)));
        const int n = 64;
        const double golden = kPi * (3.0 - std::sqrt(5.0));
        for (int k = 0; k < n; ++k) {
            const double z = 1.0 - (2.0 * k + 1.0) / n, r = std::sqrt(1.0 - z * z);
            d.push_back({r * std::cos(golden * k), r * std::sin(golden * k), z});
        }
        return d;
    }();
    return directions;
}

// Whether the solid has volume right beside x (x is in the closure of its interior).
bool besideSolid(const Node& node, const Mat4& parent, Vec3 x, const std::vector<Plane>& planes,
                 double scale) {
    const double step = kStepRel * scale, onPlane = kOnPlaneRel * scale;
    for (const Vec3& d : stepDirections())
        if (insideSolid(node, parent, x + d * step)) return true;
    // Between every three planes through x: the 8 directions on either side of each.
    std::vector<const Plane*> through;
    for (const Plane& p : planes)
        if (std::abs(glm::dot(p.n, x) - p.c) <= onPlane && through.size() < 10)
            through.push_back(&p);
    for (size_t i = 0; i < through.size(); ++i)
        for (size_t j = i + 1; j < through.size(); ++j)
            for (size_t k = j + 1; k < through.size(); ++k)
                for (int signs = 0; signs < 8; ++signs) {
                    Plane a = *through[i], b = *through[j], c = *through[k];
                    a.c = (signs & 1) ? 1.0 : -1.0;
                    b.c = (signs & 2) ? 1.0 : -1.0;
                    c.c = (signs & 4) ? 1.0 : -1.0;
                    Vec3 d;
                    if (!corner(a, b, c, d) || glm::length(d) == 0.0) continue;
                    if (insideSolid(node, parent, x + glm::normalize(d) * step)) return true;
                }
    return false;
}

// Whether x lies on the closed convex leaf's surface or inside it (only for leaves known to be
// convex; others pass).
bool withinConvexLeaf(const std::vector<Plane>& planes, size_t begin, size_t end, Vec3 x,
                      double onPlane) {
    for (size_t k = begin; k < end; ++k)
        if (std::abs(glm::dot(planes[k].n, x) - planes[k].c) > onPlane &&
            glm::dot(planes[k].n, x) > planes[k].c)
            return false;
    return true;
}

class Collector {
public:
    explicit Collector(const LeafPoints& leafPoints) : leafPoints_(leafPoints) {}

    void collect(const Node& node, const Mat4& parent, std::vector<Vec3>& out) {
        const Mat4 frame = frameOf(parent, node);
        if (node.op == Op::Leaf) {
            std::vector<Vec3> local;
            leafPoints_(node.primitive, local);
            for (const Vec3& p : local) out.push_back(transformPoint(frame, p));
            return;
        }
        if (node.op == Op::Union) {
            if (node.left) collect(*node.left, frame, out);
            if (node.right) collect(*node.right, frame, out);
            return;
        }
        std::vector<Vec3> candidates;
        if (node.left) collect(*node.left, frame, candidates);
        if (node.right) collect(*node.right, frame, candidates);
        cut(node, parent, candidates, out);
    }

    bool curvedCut = false, tooManyPlanes = false;

private:
    // The points of an intersection or difference (see Hull3D.h).
    void cut(const Node& node, const Mat4& parent, std::vector<Vec3>& candidates,
             std::vector<Vec3>& out) {
        std::vector<Leaf> leaves;
        gatherLeaves(node, parent, leaves);
        std::vector<Plane> planes;
        std::vector<size_t> leafStart{0};
        std::vector<bool> convex;
        for (size_t i = 0; i < leaves.size(); ++i) {
            if (!leafPlanes(leaves[i], uint32_t(i), planes)) curvedCut = true;
            leafStart.push_back(planes.size());
            convex.push_back(isConvex(leaves[i].node->primitive));
        }
        Bounds3 box;
        double scale = 1.0;
        for (const Vec3& p : candidates) {
            box.extend(p);
            scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        }
        const double onPlane = kOnPlaneRel * scale;
        if (!box.empty()) corners(planes, leafStart, convex, box, onPlane, candidates);
        for (const Vec3& x : candidates)
            if (besideSolid(node, parent, x, planes, scale)) out.push_back(x);
    }

    // Corners of three faces, not all of one leaf, whose boxes overlap, within the candidates'
    // box and on every convex leaf's surface they belong to.
    void corners(const std::vector<Plane>& planes, const std::vector<size_t>& leafStart,
                 const std::vector<bool>& convex, const Bounds3& box, double onPlane,
                 std::vector<Vec3>& candidates) {
        auto widened = [&](Bounds3 b) {
            b.lo -= Vec3(onPlane);
            b.hi += Vec3(onPlane);
            return b;
        };
        auto overlap = [](const Bounds3& a, const Bounds3& b) {
            Bounds3 r{glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
            return r;
        };
        std::vector<uint32_t> order(planes.size());
        std::iota(order.begin(), order.end(), 0u);
        std::vector<Bounds3> faces(planes.size());
        for (size_t i = 0; i < planes.size(); ++i)
            faces[i] = overlap(widened(planes[i].face), widened(box));
        std::sort(order.begin(), order.end(),
                  [&](uint32_t a, uint32_t b) { return faces[a].lo.x < faces[b].lo.x; });
        uint64_t tried = 0;
        for (size_t ia = 0; ia < order.size(); ++ia) {
            const Plane& a = planes[order[ia]];
            const Bounds3& fa = faces[order[ia]];
            if (fa.empty()) continue;
            for (size_t ib = ia + 1; ib < order.size(); ++ib) {
                if (faces[order[ib]].lo.x > fa.hi.x) break;
                const Bounds3 fab = overlap(fa, faces[order[ib]]);
                if (fab.empty()) continue;
                const Plane& b = planes[order[ib]];
                for (size_t ic = ib + 1; ic < order.size(); ++ic) {
                    if (faces[order[ic]].lo.x > fab.hi.x) break;
                    const Plane& c = planes[order[ic]];
                    if (a.leaf == b.leaf && b.leaf == c.leaf) continue;
                    const Bounds3 fabc = overlap(fab, faces[order[ic]]);
                    if (fabc.empty()) continue;
                    if (++tried > kMaxPlaneTriples) {
                        tooManyPlanes = true;
                        return;
                    }
                    Vec3 x;
                    if (!corner(a, b, c, x)) continue;
                    if (x.x < fabc.lo.x || x.y < fabc.lo.y || x.z < fabc.lo.z || x.x > fabc.hi.x ||
                        x.y > fabc.hi.y || x.z > fabc.hi.z)
                        continue;
                    bool onAll = true;
                    for (uint32_t leaf : {a.leaf, b.leaf, c.leaf})
                        if (convex[leaf] && !withinConvexLeaf(planes, leafStart[leaf],
                                                              leafStart[leaf + 1], x, onPlane))
                            onAll = false;
                    if (onAll) candidates.push_back(x);
                }
            }
        }
    }

    const LeafPoints& leafPoints_;
};

// The facet's vertices in order round its normal.
void orderRound(std::vector<uint32_t>& ids, const std::vector<Vec3>& points, Vec3 normal) {
    Vec3 centre(0.0);
    for (uint32_t id : ids) centre += points[id];
    centre /= double(ids.size());
    const Vec3 helper = std::abs(normal.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 e1 = glm::normalize(glm::cross(normal, helper)), e2 = glm::cross(normal, e1);
    std::vector<std::pair<double, uint32_t>> keyed;
    for (uint32_t id : ids) {
        const Vec3 v = points[id] - centre;
        keyed.push_back({std::atan2(glm::dot(v, e2), glm::dot(v, e1)), id});
    }
    std::sort(keyed.begin(), keyed.end());
    for (size_t k = 0; k < ids.size(); ++k) ids[k] = keyed[k].second;
}

}  // namespace

bool polyhedralLeafPoints(const Primitive& primitive, std::vector<Vec3>& out) {
    if (const auto* box = std::get_if<Box>(&primitive)) {
        for (int k = 0; k < 8; ++k)
            out.push_back({(k & 1) ? box->hi.x : box->lo.x, (k & 2) ? box->hi.y : box->lo.y,
                           (k & 4) ? box->hi.z : box->lo.z});
        return true;
    }
    if (const auto* poly = std::get_if<ConvexPolytope>(&primitive)) {
        if (poly->data)
            out.insert(out.end(), poly->data->vertices.begin(), poly->data->vertices.end());
        return true;
    }
    if (const auto* mesh = std::get_if<Polyhedron>(&primitive)) {
        if (mesh->data)
            out.insert(out.end(), mesh->data->vertices.begin(), mesh->data->vertices.end());
        return true;
    }
    if (const auto* e = std::get_if<Extrusion>(&primitive)) {
        // A twisted side bulges past its corners' hull; a side scaled per axis is a bilinear
        // patch, which lies within the hull of its four corners.
        if (e->kind != Extrusion::Kind::Linear || !e->outline || e->twist != 0.0 ||
            !straightEdged(*e->outline))
            return false;
        for (const Segment2& s : e->outline->segments) {
            out.push_back({s.p[0], e->z0});
            out.push_back({s.p[0] * e->scale, e->z1});
        }
        return true;
    }
    return false;
}

HullPoints hullPointsOf(const Node& solid, const LeafPoints& leafPoints) {
    HullPoints result;
    Collector collector(leafPoints);
    collector.collect(solid, Mat4(1.0), result.points);
    result.curvedCut = collector.curvedCut;
    result.tooManyPlanes = collector.tooManyPlanes;
    return result;
}

std::optional<ConvexPolytope> convexHull3D(const std::vector<Vec3>& input, std::string& why) {
    std::vector<Vec3> points;
    for (const Vec3& p : input)
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) points.push_back(p);
    std::sort(points.begin(), points.end(), [](const Vec3& a, const Vec3& b) {
        if (a.x != b.x) return a.x < b.x;
        if (a.y != b.y) return a.y < b.y;
        return a.z < b.z;
    });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.size() < 4) {
        why = "fewer than 4 distinct points";
        return std::nullopt;
    }
    std::vector<coordT> coords;
    coords.reserve(points.size() * 3);
    for (const Vec3& p : points) coords.insert(coords.end(), {p.x, p.y, p.z});

    // qhull reports its errors to a stream; keep them for the message.
    char* message = nullptr;
    size_t messageSize = 0;
    FILE* errors = open_memstream(&message, &messageSize);
    qhT qhull;
    qhT* qh = &qhull;
    qh_zero(qh, errors);
    char command[] = "qhull";
    const int exitCode =
        qh_new_qhull(qh, 3, int(points.size()), coords.data(), False, command, nullptr, errors);
    std::optional<ConvexPolytope> result;
    if (exitCode != 0) {
        if (errors) std::fflush(errors);
        why = exitCode == qh_ERRsingular || exitCode == qh_ERRprec
                  ? "the points span no volume (they lie on one plane or line)"
                  : "qhull failed";
    } else {
        std::vector<uint32_t> faceVertices, faceStarts{0};
        std::vector<uint32_t> ids;
        facetT* facet;
        vertexT *vertex, **vertexp;
        size_t facets = 0;
        FORALLfacets {
            ids.clear();
            FOREACHvertex_(facet->vertices) ids.push_back(uint32_t(qh_pointid(qh, vertex->point)));
            if (ids.size() < 3) continue;
            orderRound(ids, points, Vec3(facet->normal[0], facet->normal[1], facet->normal[2]));
            faceVertices.insert(faceVertices.end(), ids.begin(), ids.end());
            faceStarts.push_back(uint32_t(faceVertices.size()));
            ++facets;
        }
        if (facets > ConvexPolytope::kMaxPlanes) {
            why = "the hull has more than 65535 faces";
        } else {
            // Only the hull's vertices, renumbered.
            std::vector<uint32_t> remap(points.size(), UINT32_MAX);
            std::vector<Vec3> vertices;
            for (uint32_t& id : faceVertices) {
                if (remap[id] == UINT32_MAX) {
                    remap[id] = uint32_t(vertices.size());
                    vertices.push_back(points[id]);
                }
                id = remap[id];
            }
            // No origin: a hull was not faceted from anything (info names its module).
            ConvexPolytope polytope =
                ConvexPolytope::fromFaces(std::move(vertices), faceVertices, faceStarts);
            if (const char* bad = polytope.invalidReason())
                why = bad;
            else
                result = std::move(polytope);
        }
    }
    int curlong = 0, totlong = 0;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);
    if (errors) std::fclose(errors);
    std::free(message);
    return result;
}

}  // namespace csg
