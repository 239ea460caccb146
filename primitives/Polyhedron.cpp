// Notation: see primitives/Polyhedron.h. In the sheared ray frame (Woop, Benthin and Wald) a
// vertex v becomes (x, y, z) with the ray at x = y = 0 and z the ray parameter t at v's depth;
// an edge's side is E(P, Q) = Q.x P.y - Q.y P.x, positive when the ray passes left of P -> Q.
#include "primitives/Polyhedron.h"

#include "primitives/SpanCapacity.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <type_traits>

#include "primitives/base/Fma.h"
#include "primitives/base/GroupByKey.h"
#include "primitives/base/PointWelder.h"
#include "primitives/base/Tolerances.h"
#include "primitives/base/TrianglePoint.h"
#include "primitives/solvers/LinePoint.h"

namespace csg {

namespace {

// ---- the crossing test ----

// The ray in its sheared frame: axis kz is the largest component of d, kx and ky the others in
// an order that keeps the frame right-handed (swapped when d[kz] < 0, so a triangle's winding
// reads the same).
struct ShearedRay {
    Vec3 o;
    int kx, ky, kz;
    double sx, sy, sz;

    ShearedRay(const Vec3& origin, const Vec3& d) : o(origin) {
        const Vec3 a = glm::abs(d);
        kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
        kx = (kz + 1) % 3;
        ky = (kx + 1) % 3;
        if (d[kz] < 0.0) std::swap(kx, ky);
        sx = d[kx] / d[kz];
        sy = d[ky] / d[kz];
        sz = 1.0 / d[kz];
    }
};

struct Projected {
    double x, y, z;
};

// v in the ray's frame. The same operations for every triangle that shares v, so an edge's two
// triangles see the same endpoints, bit for bit.
inline Projected project(const ShearedRay& r, const Vec3& v) {
    const double ax = v[r.kx] - r.o[r.kx], ay = v[r.ky] - r.o[r.ky], az = v[r.kz] - r.o[r.kz];
    return {ax - r.sx * az, ay - r.sy * az, r.sz * az};
}

// The sign of an exact sum of four doubles: Shewchuk's grow-expansion (with zero elimination)
// turns them into a non-overlapping expansion whose largest component carries the sign.
int signOfExactSum(const double (&terms)[4]) {
    double e[4];
    int n = 0;
    for (const double b : terms) {
        double q = b;
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const double s = e[i] + q;  // Knuth's two-sum: s + err == e[i] + q exactly
            const double bv = s - e[i];
            const double err = (e[i] - (s - bv)) + (q - bv);
            if (err != 0.0) e[m++] = err;
            q = s;
        }
        if (q != 0.0) e[m++] = q;
        n = m;
    }
    return n == 0 ? 0 : (e[n - 1] > 0.0 ? 1 : -1);
}

// The side of edge P -> Q where the filter could not tell: the exact determinant from
// error-free products, and where it is zero the simulation of simplicity's answer for the ray
// moved by (eps, eps^2): E = E0 + eps (Q.y - P.y) + eps^2 (P.x - Q.x). Antisymmetric in
// (P, Q), so the edge's two triangles always see opposite sides. 0 only for an edge whose
// ends project to one point (its triangles then have no projected area: never crossed).
[[gnu::noinline]] int exactEdgeSign(const Projected& p, const Projected& q) {
    const double a = q.x * p.y, b = q.y * p.x;
    const double errA = fusedMultiplyAdd(q.x, p.y, -a), errB = fusedMultiplyAdd(q.y, p.x, -b);
    if (const int s = signOfExactSum({a, -b, errA, -errB}); s != 0) return s;
    if (q.y != p.y) return q.y > p.y ? 1 : -1;
    if (p.x != q.x) return p.x > q.x ? 1 : -1;
    return 0;
}

// The side of edge P -> Q when the rounded determinant is certainly of the true sign, else 0
// ("ask exactEdgeSign"): e = fl(fl(a) - fl(b)) is within tol::kEdgeSignFilter (|a| + |b|) of
// the exact a - b.
inline int filteredSign(double a, double b, double e) {
    if (std::abs(e) > tol::kEdgeSignFilter * (std::abs(a) + std::abs(b))) return e > 0.0 ? 1 : -1;
    return 0;
}

// Whether the line crosses triangle (A, B, C) by the rule of Polyhedron.h, and where (t).
inline bool crosses(const Projected& A, const Projected& B, const Projected& C, double& t) {
    // Step 1: the three edge functions, U of B -> C, V of C -> A, W of A -> B.
    const double ua = C.x * B.y, ub = C.y * B.x, U = ua - ub;
    const double va = A.x * C.y, vb = A.y * C.x, V = va - vb;
    const double wa = B.x * A.y, wb = B.y * A.x, W = wa - wb;
    int su = filteredSign(ua, ub, U), sv = filteredSign(va, vb, V), sw = filteredSign(wa, wb, W);
    // Step 2: two certain signs that differ: the ray passes outside (the common case).
    const bool anyPositive = su > 0 || sv > 0 || sw > 0, anyNegative = su < 0 || sv < 0 || sw < 0;
    if (anyPositive && anyNegative) return false;
    // Step 3: the uncertain ones exactly, with the tie-break.
    if (su == 0) su = exactEdgeSign(B, C);
    if (sv == 0) sv = exactEdgeSign(C, A);
    if (sw == 0) sw = exactEdgeSign(A, B);
    if (su == 0 || su != sv || sv != sw) return false;
    // Step 4: t from the barycentric weights; where they lost all their digits (a ray at a
    // vertex of a sliver), the mean depth. Clamped to the corners' depths, which bound it.
    const double det = U + V + W;
    t = (U * A.z + V * B.z + W * C.z) / det;
    if (!std::isfinite(t) || (det > 0.0) != (su > 0)) t = (A.z + B.z + C.z) / 3.0;
    t = std::clamp(t, std::min({A.z, B.z, C.z}), std::max({A.z, B.z, C.z}));
    return true;
}

// ---- the lecture's methods (Polyhedron.h): each triangle alone, in rounded arithmetic ----

// The axis of n's largest component, and the two after it in cyclic order, so that
// cross(a, b)[i0] = a[i1] b[i2] - a[i2] b[i1].
struct DroppedAxis {
    int i0, i1, i2;
    explicit DroppedAxis(const Vec3& n) {
        const Vec3 a = glm::abs(n);
        i0 = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
        i1 = (i0 + 1) % 3;
        i2 = (i0 + 2) % 3;
    }
    Vec2 of(const Vec3& v) const { return Vec2(v[i1], v[i2]); }
};

double cross2(const Vec2& a, const Vec2& b) {
    return a.x * b.y - a.y * b.x;
}

// Both methods' first step: where the line meets the triangle's plane (t), that point in the
// projection that drops the normal's largest axis, and that axis; nullopt when the line runs
// along the plane.
struct PlanePoint {
    Vec3 n;  // cross(P1 - P0, P2 - P0)
    DroppedAxis axis;
    Vec2 at;
};
inline std::optional<PlanePoint> planePoint(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                            const Vec3& o, const Vec3& d, double& t) {
    const Vec3 n = glm::cross(p1 - p0, p2 - p0);
    const double along = glm::dot(n, d);
    if (along == 0.0) return std::nullopt;
    t = glm::dot(n, p0 - o) / along;
    if (!std::isfinite(t)) return std::nullopt;
    const DroppedAxis axis(n);
    return PlanePoint{n, axis, Vec2(o[axis.i1] + t * d[axis.i1], o[axis.i2] + t * d[axis.i2])};
}

// Snyder's barycentric coordinates of the plane point q (projected) in triangle (a, b, c).
inline std::array<double, 3> snyderWeights(const Vec2& a, const Vec2& b, const Vec2& c,
                                           const Vec2& q, double n0) {
    return {cross2(c - b, q - b) / n0, cross2(a - c, q - c) / n0, cross2(b - a, q - a) / n0};
}

struct SnyderTest {
    bool operator()(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& o, const Vec3& d,
                    double& t) const {
        const std::optional<PlanePoint> q = planePoint(p0, p1, p2, o, d, t);
        if (!q) return false;
        const DroppedAxis& axis = q->axis;
        const std::array<double, 3> b =
            snyderWeights(axis.of(p0), axis.of(p1), axis.of(p2), q->at, q->n[axis.i0]);
        return b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0 && b[0] <= 1.0 && b[1] <= 1.0 &&
               b[2] <= 1.0;
    }
};

// Marchal's test of the plane point (w = I - P0, projected) against the edge P1 P2 (a = P1 - P0,
// b = P2 - P0): where the half-line from P0 through I crosses it, as M = a + s (b - a), and
// r = |P0 I| / |P0 M|; nullopt when it does not cross it.
struct MarchalPoint {
    double s, r;
};
inline std::optional<MarchalPoint> marchalPoint(const Vec2& a, const Vec2& b, const Vec2& w) {
    // The u coordinates (across the half-line, scaled by |w|) of P1 and P2: opposite signs.
    const double ua = cross2(w, a), ub = cross2(w, b);
    if (!(ua * ub < 0.0)) return std::nullopt;
    const double s = ua / (ua - ub);
    const Vec2 m = a + s * (b - a);
    // |w| |P0 M| when M lies ahead on the half-line (its v coordinate, scaled by |w|).
    const double along = glm::dot(m, w);
    if (!(along > 0.0)) return std::nullopt;
    return MarchalPoint{s, glm::dot(w, w) / along};
}

struct MarchalTest {
    bool operator()(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& o, const Vec3& d,
                    double& t) const {
        const std::optional<PlanePoint> q = planePoint(p0, p1, p2, o, d, t);
        if (!q) return false;
        const Vec2 origin = q->axis.of(p0);
        const std::optional<MarchalPoint> m =
            marchalPoint(q->axis.of(p1) - origin, q->axis.of(p2) - origin, q->at - origin);
        return m && m->r < 1.0;
    }
};

// ---- building ----

// The direction inside() and the orientation test cast along: no symmetry of a test part lines
// up with it, so a ray along it rarely runs through an edge (and the rule handles it if it
// does).
const Vec3 kInsideDirection = glm::normalize(Vec3(0.5711, 0.6289, 0.5277));

// Mesh BVH: up to two triangles per leaf slot, a box test costing as much as a triangle test
// (bench/README.md, polygon meshes: 1, 2 and 4 per slot ran within noise of each other; 2
// needs half the nodes of 1).
constexpr BvhBuildOptions kMeshBvhOptions{.maxLeafItems = 2, .traversalCost = 1.0};

// Faces of more corners than this that are not convex in their projection are cut into a fan
// rather than ear-clipped (ear clipping is quadratic in the corners); under crossing parity a
// fan covers a planar polygon exactly (its folded triangles cancel in pairs).
constexpr size_t kMaxEarClipCorners = 4096;

// Welds points of equal position (-0 == +0): returns each point's welded index and leaves the
// distinct positions in `points`, in order of first appearance, zeros as +0.
std::vector<uint32_t> weld(std::vector<Vec3>& points) {
    PointWelder welder(points.size());
    std::vector<uint32_t> welded(points.size());
    for (size_t i = 0; i < points.size(); ++i) welded[i] = welder.add(points[i] + Vec3(0.0));
    points = welder.take();
    return welded;
}

using Triangle = std::array<uint32_t, 3>;

// The triangles' boxes, widened by the crossing test's margin (tol::kMeshBoxMarginRel of the
// mesh box's diagonal): what every structure over them is built on.
std::vector<Bounds3> triangleBoxes(const std::vector<Vec3>& points,
                                   const std::vector<Triangle>& triangles, const Bounds3& meshBox) {
    const double margin = tol::kMeshBoxMarginRel * glm::length(meshBox.extent());
    std::vector<Bounds3> boxes(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        for (const uint32_t v : triangles[i]) boxes[i].extend(points[v]);
        boxes[i].lo -= Vec3(margin);
        boxes[i].hi += Vec3(margin);
    }
    return boxes;
}

// The polygon's corners in 2-D: the two axes other than the Newell normal's largest, in cyclic
// order, so the polygon's turn there has the sign of that normal component.
struct PlanarPolygon {
    std::vector<Vec2> at;
    double orientation = 1.0;  // sign of the projected area
};

PlanarPolygon projectFace(const std::vector<Vec3>& points, const std::vector<uint32_t>& face) {
    Vec3 n(0.0);
    for (size_t i = 0; i < face.size(); ++i) {
        const Vec3 &p = points[face[i]], &q = points[face[(i + 1) % face.size()]];
        n += Vec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
    }
    const Vec3 a = glm::abs(n);
    const int drop = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    PlanarPolygon poly;
    poly.orientation = n[drop] < 0.0 ? -1.0 : 1.0;
    for (const uint32_t c : face) poly.at.emplace_back(points[c][u], points[c][v]);
    return poly;
}

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Convex (no turn against the orientation) and winding once: the polygon's edge directions
// sweep 360 degrees, so its x coordinate changes direction at most twice.
bool isConvex(const PlanarPolygon& poly) {
    const size_t k = poly.at.size();
    int flips = 0;
    double lastDx = 0.0;
    for (size_t i = 0; i < k; ++i) {
        const Vec2 &a = poly.at[(i + k - 1) % k], &b = poly.at[i], &c = poly.at[(i + 1) % k];
        if (cross2(a, b, c) * poly.orientation < 0.0) return false;
        const double dx = c.x - b.x;
        if (dx != 0.0) {
            if (lastDx != 0.0 && (dx > 0.0) != (lastDx > 0.0)) ++flips;
            lastDx = dx;
        }
    }
    return flips <= 2;
}

// Ear clipping in the projection: cut a corner that turns with the polygon and holds no other
// corner; where rounding leaves none, the first convex corner (else the first corner) is cut,
// so it always ends.
void earClip(const std::vector<uint32_t>& face, const PlanarPolygon& poly,
             std::vector<Triangle>& out) {
    const size_t k = face.size();
    std::vector<uint32_t> next(k), prev(k);
    for (size_t i = 0; i < k; ++i)
        next[i] = uint32_t((i + 1) % k), prev[i] = uint32_t((i + k - 1) % k);
    const double s = poly.orientation;
    auto isEar = [&](uint32_t i) {
        const Vec2 &a = poly.at[prev[i]], &b = poly.at[i], &c = poly.at[next[i]];
        if (!(cross2(a, b, c) * s > 0.0)) return false;
        for (uint32_t j = next[next[i]]; j != prev[i]; j = next[j]) {
            const Vec2& p = poly.at[j];
            if (p == a || p == b || p == c) continue;
            if (cross2(a, b, p) * s >= 0.0 && cross2(b, c, p) * s >= 0.0 &&
                cross2(c, a, p) * s >= 0.0)
                return false;
        }
        return true;
    };
    uint32_t at = 0;
    for (size_t left = k; left > 3; --left) {
        uint32_t cut = at, convex = UINT32_MAX;
        bool found = false;
        for (size_t tries = 0; tries < left; ++tries, cut = next[cut]) {
            if (isEar(cut)) {
                found = true;
                break;
            }
            const Vec2 &a = poly.at[prev[cut]], &b = poly.at[cut], &c = poly.at[next[cut]];
            if (convex == UINT32_MAX && cross2(a, b, c) * s > 0.0) convex = cut;
        }
        if (!found) cut = convex != UINT32_MAX ? convex : at;
        out.push_back({face[prev[cut]], face[cut], face[next[cut]]});
        next[prev[cut]] = next[cut];
        prev[next[cut]] = prev[cut];
        at = next[cut];
    }
    out.push_back({face[prev[at]], face[at], face[next[at]]});
}

// Triangles of the faces, in welded indices; faces of fewer than 3 distinct corners dropped.
std::vector<Triangle> triangulate(const std::vector<Vec3>& points,
                                  const std::vector<uint32_t>& welded, const PolygonFaces& faces,
                                  uint64_t& dropped) {
    std::vector<Triangle> out;
    out.reserve(faces.corners.size() >= 2 * faces.size() ? faces.corners.size() - 2 * faces.size()
                                                         : faces.size());
    std::vector<uint32_t> face;
    for (size_t f = 0; f < faces.size(); ++f) {
        // Step 1: welded corners, repeats in a row (and around) removed.
        face.clear();
        for (uint32_t i = faces.faceStart[f]; i < faces.faceStart[f + 1]; ++i) {
            const uint32_t c = welded[faces.corners[i]];
            if (face.empty() || face.back() != c) face.push_back(c);
        }
        while (face.size() > 1 && face.back() == face.front()) face.pop_back();
        if (face.size() < 3) {
            ++dropped;
            continue;
        }
        if (face.size() == 3) {
            out.push_back({face[0], face[1], face[2]});
            continue;
        }
        // Step 2: a fan where the projection is convex, else ear clipping.
        const PlanarPolygon poly = projectFace(points, face);
        if (isConvex(poly) || face.size() > kMaxEarClipCorners) {
            for (size_t i = 1; i + 1 < face.size(); ++i)
                out.push_back({face[0], face[i], face[i + 1]});
        } else {
            earClip(face, poly, out);
        }
    }
    // A triangle with a repeated corner has no area and cancels out of every edge count.
    const auto repeated = [](const Triangle& t) {
        return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    };
    dropped += static_cast<uint64_t>(std::count_if(out.begin(), out.end(), repeated));
    out.erase(std::remove_if(out.begin(), out.end(), repeated), out.end());
    return out;
}

// Edge statistics, and the sheets: triangles joined across edges of exactly two triangles,
// each turned (flip) so that the pair runs the edge in opposite directions. Returns each
// triangle's sheet; flip[i] says whether triangle i was turned relative to its sheet's first.
std::vector<uint32_t> findSheets(const std::vector<Triangle>& triangles, size_t vertexCount,
                                 MeshEdges& stats, std::vector<uint8_t>& flip,
                                 uint32_t& sheetCount) {
    const size_t n = triangles.size();
    // Step 1: every triangle's three edges, grouped by their lower vertex (a counting sort, so
    // each group lists its triangles in order), each group then ordered by the upper vertex: the
    // uses of one edge lie together. Sorting all the uses by (low, high) took 8 % of a
    // large mesh's load (bench/README.md, "Loading a large mesh").
    struct EdgeUse {
        uint32_t high;
        uint32_t triangle;
        bool forward;  // runs low -> high
    };
    Grouped<EdgeUse> byLow = groupByKey<EdgeUse>(vertexCount, [&](auto&& emit) {
        for (uint32_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = triangles[i][k], b = triangles[i][(k + 1) % 3];
                emit(std::min(a, b), EdgeUse{std::max(a, b), i, a < b});
            }
    });
    const std::vector<uint32_t>& groupStart = byLow.start;
    std::vector<EdgeUse>& uses = byLow.values;
    // Insertion sort, stable, in place: a vertex has a few edges, and std::stable_sort would
    // allocate a buffer for each group. A hub of many edges (a fan's) takes std::stable_sort,
    // so no group is sorted in quadratic time.
    const auto byHigh = [](const EdgeUse& x, const EdgeUse& y) { return x.high < y.high; };
    for (size_t v = 0; v < vertexCount; ++v) {
        EdgeUse *first = uses.data() + groupStart[v], *last = uses.data() + groupStart[v + 1];
        if (last - first > 32) {
            std::stable_sort(first, last, byHigh);
            continue;
        }
        for (EdgeUse* at = first + 1; at < last; ++at)
            for (EdgeUse* p = at; p > first && byHigh(p[0], p[-1]); --p) std::swap(p[0], p[-1]);
    }
    // Step 2: count, and link the triangles of two-triangle edges; the links grouped by
    // triangle (each triangle's in the order of its edges' (low, high)).
    struct Link {
        uint32_t other;
        bool sameWay;  // both run the edge the same way: one of them must turn
    };
    struct Pair {
        uint32_t a, b;
        bool sameWay;
    };
    std::vector<Pair> pairs;
    for (size_t v = 0; v < vertexCount; ++v) {
        for (uint32_t i = groupStart[v]; i < groupStart[v + 1];) {
            uint32_t j = i;
            while (j < groupStart[v + 1] && uses[j].high == uses[i].high) ++j;
            const uint32_t count = j - i;
            ++stats.edges;
            if (count % 2 == 1) ++stats.openEdges;
            if (count > 2) ++stats.manyFaces;
            if (count == 2) {
                const bool sameWay = uses[i].forward == uses[i + 1].forward;
                if (sameWay) ++stats.misoriented;
                pairs.push_back({uses[i].triangle, uses[i + 1].triangle, sameWay});
            }
            i = j;
        }
    }
    byLow = {};
    const Grouped<Link> links = groupByKey<Link>(n, [&](auto&& emit) {
        for (const Pair& p : pairs)
            emit(p.a, Link{p.b, p.sameWay}), emit(p.b, Link{p.a, p.sameWay});
    });
    pairs = {};
    // Step 3: breadth first over the links, each sheet from its lowest triangle.
    constexpr uint32_t kNone = UINT32_MAX;
    std::vector<uint32_t> sheet(n, kNone);
    flip.assign(n, 0);
    sheetCount = 0;
    std::vector<uint32_t> queue;
    for (uint32_t seed = 0; seed < n; ++seed) {
        if (sheet[seed] != kNone) continue;
        sheet[seed] = sheetCount;
        queue.assign(1, seed);
        for (size_t q = 0; q < queue.size(); ++q) {
            const uint32_t t = queue[q];
            for (uint32_t l = links.start[t]; l < links.start[t + 1]; ++l) {
                const Link& link = links.values[l];
                if (sheet[link.other] != kNone) continue;  // a conflict (a Klein bottle) stays
                sheet[link.other] = sheetCount;
                flip[link.other] = flip[t] ^ uint8_t(link.sameWay);
                queue.push_back(link.other);
            }
        }
        ++sheetCount;
    }
    return sheet;
}

}  // namespace

Polyhedron Polyhedron::make(std::vector<Vec3> points, const PolygonFaces& faces) {
    auto data = std::make_shared<PolyhedronData>();
    Polyhedron mesh{nullptr, PolygonMethod::Watertight, nullptr};
    for (const Vec3& p : points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            data->invalid = "mesh points must be finite";
    if (data->invalid) return mesh.data = data, mesh;

    // Step 1: weld, triangulate, drop what has no area.
    const std::vector<uint32_t> welded = weld(points);
    std::vector<Triangle> triangles = triangulate(points, welded, faces, data->droppedFaces);
    if (triangles.empty()) data->invalid = kNoFaces;
    if (triangles.size() > kMaxTriangles) data->invalid = "a mesh holds at most 2^24 triangles";
    if (data->invalid) return mesh.data = data, mesh;

    // Step 2: edges and sheets, each sheet wound one way.
    std::vector<uint8_t> flip;
    uint32_t sheetCount = 0;
    std::vector<uint32_t> sheet =
        findSheets(triangles, points.size(), data->edges, flip, sheetCount);
    for (size_t i = 0; i < triangles.size(); ++i)
        if (flip[i]) std::swap(triangles[i][1], triangles[i][2]);

    // Step 3: the BVH over triangle boxes widened by the margin of the crossing test.
    for (const Vec3& p : points) data->box.extend(p);
    std::vector<Bounds3> boxes = triangleBoxes(points, triangles, data->box);
    std::vector<uint32_t> order;
    data->root = buildWideBvh(boxes, order, 0, kMeshBvhOptions, data->nodes);
    boxes = {};

    // Step 4: triangles in leaf order, vertices in order of first use (a leaf's corners sit
    // together in memory).
    std::vector<uint32_t> renumber(points.size(), UINT32_MAX);
    data->triangles.resize(triangles.size());
    std::vector<uint32_t> sheetOf(triangles.size());
    for (size_t i = 0; i < order.size(); ++i) {
        Triangle t = triangles[order[i]];
        for (uint32_t& v : t) {
            if (renumber[v] == UINT32_MAX) {
                renumber[v] = static_cast<uint32_t>(data->vertices.size());
                data->vertices.push_back(points[v]);
            }
            v = renumber[v];
        }
        data->triangles[i] = t;
        sheetOf[i] = sheet[order[i]];
    }
    triangles = {};
    sheet = {};

    // Step 5: turn each sheet whose normals point into the solid: from the centroid of its
    // largest triangle, along that triangle's normal, an odd count of crossings ahead.
    mesh.data = data;
    std::vector<uint32_t> largest(sheetCount, UINT32_MAX);
    std::vector<double> largestArea(sheetCount, -1.0);
    const auto normalOf = [&](uint32_t i) {
        const Triangle& t = data->triangles[i];
        const Vec3 &a = data->vertices[t[0]], &b = data->vertices[t[1]], &c = data->vertices[t[2]];
        return glm::cross(b - a, c - a);
    };
    for (uint32_t i = 0; i < data->triangles.size(); ++i) {
        const double area = glm::length(normalOf(i));
        if (area > largestArea[sheetOf[i]]) largestArea[sheetOf[i]] = area, largest[sheetOf[i]] = i;
    }
    std::vector<uint8_t> turnSheet(sheetCount, 0);
    std::vector<Crossing> found;
    for (uint32_t s = 0; s < sheetCount; ++s) {
        const uint32_t i = largest[s];
        const Vec3 n = normalOf(i);
        if (!(largestArea[s] > 0.0)) continue;  // a sheet of no area: no side to choose
        const Triangle& t = data->triangles[i];
        const Vec3 centroid =
            (data->vertices[t[0]] + data->vertices[t[1]] + data->vertices[t[2]]) / 3.0;
        mesh.crossings(centroid, n, found);
        int ahead = 0;
        for (const Crossing& c : found) ahead += c.t > 0.0 && c.triangle != i;
        turnSheet[s] = ahead % 2 == 1;
    }
    for (uint32_t i = 0; i < data->triangles.size(); ++i)
        if (turnSheet[sheetOf[i]]) std::swap(data->triangles[i][1], data->triangles[i][2]);
    return mesh;
}

const char* Polyhedron::invalidReason() const {
    return data ? data->invalid : "mesh was not built";
}

Bounds3 Polyhedron::bounds() const {
    return data && !data->invalid ? data->box : Bounds3{Vec3(0.0), Vec3(0.0)};
}

const MeshEdges& Polyhedron::edges() const {
    return data->edges;
}

size_t Polyhedron::triangleCount() const {
    return data ? data->triangles.size() : 0;
}

void Polyhedron::describe(JsonWriter& json) const {
    json.key("triangles").value(uint64_t(data ? data->triangles.size() : 0));
    json.key("vertices").value(uint64_t(data ? data->vertices.size() : 0));
    json.key("closed").value(data && data->edges.closed());
}

std::shared_ptr<const MeshStructure> Polyhedron::organize(const PolyhedronData& data, Accel accel) {
    // auto keeps the SAH (bench/README.md, "A mesh's faces": a terrain of 10^3 .. 10^6
    // triangles): it traced shadow and reflected rays as fast as any structure or faster at
    // every size, in a tenth to a half of a uniform grid's memory; the grid, which auto would
    // take for evenly spread objects, traced primary rays up to 1.8x faster from 10^4 up, but
    // shadow rays at 0.3-1.0x and reflections at 0.5-0.8x the SAH's rate.
    if (accel == Accel::Sah || accel == Accel::Auto || data.invalid) return nullptr;
    const std::vector<Bounds3> boxes = triangleBoxes(data.vertices, data.triangles, data.box);
    auto out = std::make_shared<MeshStructure>();
    out->accel = accel;
    if (accel == Accel::Grid) {
        out->grid = buildUniformGrid(boxes, 0);
    } else if (accel == Accel::NonUniformGrid) {
        out->halving = buildHalvingGrid(boxes, 0);
    } else {
        BvhBuildOptions options = kMeshBvhOptions;
        options.method = accel == Accel::Median ? BvhMethod::Median : BvhMethod::GoldsmithSalmon;
        out->root = buildWideBvh(boxes, out->leafTriangles, 0, options, out->nodes);
    }
    return out;
}

size_t MeshStructure::bytes() const {
    return sizeof(*this) + sizeof(BvhNode) * nodes.capacity() + 4 * leafTriangles.capacity() +
           grid.bytes() + halving.bytes();
}

namespace {

// The watertight test, on the sheared frame's projections.
struct WatertightTest {
    ShearedRay ray;
    bool operator()(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3&, const Vec3&,
                    double& t) const {
        return crosses(project(ray, p0), project(ray, p1), project(ray, p2), t);
    }
};

// Calls leaf(first, count) for each leaf of the wide BVH whose box the line meets between lo
// and `horizon`, nearer slots first (by the direction's octant, as csg/'s walk orders them); leaf
// may lower the horizon, and a slot that begins past it is not entered: every leaf whose box
// begins at or before the final horizon is visited.
template <class Leaf>
void forEachBvhLeaf(const std::vector<BvhNode>& nodes, uint32_t root, const Vec3& o, const Vec3& d,
                    double lo, const double& horizon, Leaf&& leaf) {
    const SlabRay slab(o, d);
    const unsigned octant = octantOf(d);
    struct Pending {
        double tNear;
        uint32_t target, leafCount;
    };
    Pending todo[3 * kBvhMaxDepth + 4];
    int pending = 0;
    const BvhNode* node = &nodes[root];
    for (;;) {
        alignas(32) double near[4];
        const unsigned hits = clipToBoxes(slab, node->boxes, lo, horizon, near) & node->usedMask();
        const unsigned order = node->order[octant];
        for (int i = node->slots - 1; i >= 0; --i) {
            const unsigned k = order >> (2 * i) & 3u;
            if (hits >> k & 1u) todo[pending++] = {near[k], node->slot[k], node->leafCount[k]};
        }
        for (;;) {
            if (pending == 0) return;
            const Pending& next = todo[--pending];
            if (next.tNear > horizon) continue;
            if (next.leafCount == 0) {
                node = &nodes[next.target];
                break;
            }
            leaf(next.target, next.leafCount);
        }
    }
}

// The grids' mailbox, per thread: triangle i was tested in this walk when stamp[i] == walk.
// Sized to the largest mesh walked; a new number per walk, every stamp cleared on the wrap.
thread_local std::vector<uint32_t> mailboxStamp;
thread_local uint32_t mailboxWalk = 0;

uint32_t startMailbox(size_t triangles) {
    if (mailboxStamp.size() < triangles) mailboxStamp.resize(triangles);
    if (++mailboxWalk == 0) {
        std::fill(mailboxStamp.begin(), mailboxStamp.end(), 0u);
        mailboxWalk = 1;
    }
    return mailboxWalk;
}

// Calls triangle(i) once for each triangle listed by a cell of the grid that the line meets
// between lo and `horizon`, nearer cells first; triangle may lower the horizon. (Every triangle
// when the line meets the box along no finite stretch, which a line with d != 0 never does.)
template <class Grid, class Visit>
void forEachGridTriangle(const Grid& g, size_t triangles, const Vec3& o, const Vec3& d, double lo,
                         double& horizon, Visit&& triangle) {
    const SlabRay slab(o, d);
    double tIn = lo, tOut = kInfinity;
    if (!clipToBox(slab, g.box, tIn, tOut)) return;
    const uint32_t walk = startMailbox(triangles);
    const auto cell = [&](const uint32_t* items, uint32_t count) {
        for (uint32_t k = 0; k < count; ++k) {
            const uint32_t i = items[k];
            if (mailboxStamp[i] == walk) continue;
            mailboxStamp[i] = walk;
            triangle(i);
        }
        return true;
    };
    if (!std::isfinite(tIn) || !std::isfinite(tOut)) {
        cell(g.items.data(), static_cast<uint32_t>(g.items.size()));
        return;
    }
    uint64_t visits = 0;
    if constexpr (std::is_same_v<Grid, UniformGrid>)
        walkUniformGrid(g, o, d, slab.invD, tIn, tOut, horizon, visits, cell);
    else
        walkHalvingGrid(g, o, slab.invD, tIn, tOut, horizon, visits, cell);
}

// Every crossing of the line with the mesh's triangles by `test`, unsorted, appended to out,
// found through the mesh's own BVH or `structure`: all of them, or, from lo (a lower bound) up
// to a finite horizon, at least every one between the two (found(t) is told each crossing found,
// and may lower the horizon). The line's origin must lie near the mesh's box (the BVH margin
// assumes it: see Polyhedron.h).
template <class Test, class Found>
void collectCrossingsBy(const Test& test, const PolyhedronData& mesh,
                        const MeshStructure* structure, const Vec3& o, const Vec3& d, double lo,
                        double& horizon, Found&& found, std::vector<Polyhedron::Crossing>& out) {
    const auto cross = [&](uint32_t i) {
        const std::array<uint32_t, 3>& t = mesh.triangles[i];
        double at;
        if (test(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], o, d, at)) {
            out.push_back({at, i});
            found(at);
        }
    };
    if (!structure) {
        // The SAH BVH's leaves hold the triangles in their own order.
        return forEachBvhLeaf(mesh.nodes, mesh.root, o, d, lo, horizon,
                              [&](uint32_t first, uint32_t count) {
                                  for (uint32_t i = first; i < first + count; ++i) cross(i);
                              });
    }
    const size_t n = mesh.triangles.size();
    switch (structure->accel) {
        case Accel::Grid:
            return forEachGridTriangle(structure->grid, n, o, d, lo, horizon, cross);
        case Accel::NonUniformGrid:
            return forEachGridTriangle(structure->halving, n, o, d, lo, horizon, cross);
        default:  // median cut, Goldsmith-Salmon (organize() gives no other)
            return forEachBvhLeaf(structure->nodes, structure->root, o, d, lo, horizon,
                                  [&](uint32_t first, uint32_t count) {
                                      for (uint32_t k = first; k < first + count; ++k)
                                          cross(structure->leafTriangles[k]);
                                  });
    }
}

// collectCrossingsBy with the polygon method's test.
template <class Found>
void collectCrossingsUpTo(const PolyhedronData& mesh, const Vec3& o, const Vec3& d,
                          PolygonMethod method, const MeshStructure* structure, double lo,
                          double& horizon, Found&& found, std::vector<Polyhedron::Crossing>& out) {
    if (!(d.x != 0.0 || d.y != 0.0 || d.z != 0.0)) return;
    switch (method) {
        case PolygonMethod::Watertight:
            return collectCrossingsBy(WatertightTest{ShearedRay(o, d)}, mesh, structure, o, d, lo,
                                      horizon, found, out);
        case PolygonMethod::Snyder:
            return collectCrossingsBy(SnyderTest{}, mesh, structure, o, d, lo, horizon, found, out);
        case PolygonMethod::Marchal:
            return collectCrossingsBy(MarchalTest{}, mesh, structure, o, d, lo, horizon, found,
                                      out);
    }
}

// Every crossing of the line.
void collectCrossings(const PolyhedronData& mesh, const Vec3& o, const Vec3& d,
                      std::vector<Polyhedron::Crossing>& out,
                      PolygonMethod method = PolygonMethod::Watertight,
                      const MeshStructure* structure = nullptr) {
    double horizon = kInfinity;
    collectCrossingsUpTo(
        mesh, o, d, method, structure, -kInfinity, horizon, [](double) {}, out);
}

bool crossingBefore(const Polyhedron::Crossing& a, const Polyhedron::Crossing& b) {
    return a.t < b.t || (a.t == b.t && a.triangle < b.triangle);
}

void sortCrossings(std::vector<Polyhedron::Crossing>& c) {
    if (c.size() == 2) {
        if (crossingBefore(c[1], c[0])) std::swap(c[0], c[1]);
        return;
    }
    std::sort(c.begin(), c.end(), crossingBefore);
}

// Per thread, grown to the most crossings a line has had: no allocation per ray after that.
thread_local std::vector<Polyhedron::Crossing> lineCrossings;
thread_local std::vector<LocalSpans::Entry> lineSpans;

// spans() for a caller that reads only the first span past `from` (LocalSpans::firstOnly), of a
// closed mesh, whose crossings pair up along every line. The crossings are gathered nearer
// boxes first, up to a horizon that each crossing past from + margin lowers to itself plus
// twice the margin; every crossing at or before the final horizon is then known, and so is
// the pairing up to it (from the line's first crossing). The spans past `from` up to the first
// whose part past `from` is longer than the margin are answered from those alone: entries and
// exits exact within the horizon (a ray that starts inside a span meets its exit past `from`,
// which sets the horizon past it); the first span's exit, past the horizon, is given as the
// horizon when the span begins more than the margin past `from` (no crossing lies before it,
// and its part past `from` is then twice the margin long, as LocalSpans allows). False, with
// nothing written, where the whole list must answer: an exit past the horizon that must be
// exact, a touch (two crossings at one t) past from + margin, or a span needed past the
// horizon after a short one. A ray so walks the boxes up to its first crossings, not every
// box along the line.
bool firstSpanOfClosedMesh(const PolyhedronData& mesh, const MeshStructure* structure,
                           PolygonMethod method, const Vec3& o, const Vec3& d, LocalSpans& out) {
    std::vector<Polyhedron::Crossing>& c = lineCrossings;
    c.clear();
    const double past = out.from + out.margin;
    double horizon = out.to + out.margin;  // nothing past it is read
    // A line whose `from` lies inside the mesh's box (a ray leaving a surface, toward a light
    // or as a reflection) is first searched from `from` on only, and stops at its first
    // crossing there. None up to the box's far side is an even count past `from` (none), so
    // `from` is outside and no span lies past it: then the crossings behind `from`, back to
    // the line's start, which the pairing would need, are never gathered.
    double tIn = -kInfinity, tOut = kInfinity;
    if (clipToBox(SlabRay(o, d), mesh.box, tIn, tOut) && out.from > tIn &&
        horizon > tOut + out.margin) {
        bool ahead = false;
        double until = horizon;
        collectCrossingsUpTo(
            mesh, o, d, method, structure, out.from, until,
            [&](double t) {
                if (t >= out.from) ahead = true, until = -kInfinity;
            },
            c);
        if (!ahead) return true;
        c.clear();
    }
    collectCrossingsUpTo(
        mesh, o, d, method, structure, -kInfinity, horizon,
        [&](double t) {
            if (t > past) horizon = std::min(horizon, t + 2.0 * out.margin);
        },
        c);
    sortCrossings(c);
    size_t known = 0;  // the crossings at or before the horizon
    while (known < c.size() && c[known].t <= horizon) ++known;
    const auto wholeListNeeded = [&] {
        out.count = 0;
        return false;
    };
    for (size_t i = 0; i < known; i += 2) {
        const bool paired = i + 1 < known;
        if (paired && c[i].t == c[i + 1].t) {
            if (c[i].t > past) return wholeListNeeded();
            continue;
        }
        if (paired && c[i + 1].t < out.from) continue;  // ends before `from`
        const uint16_t faceIn = Polyhedron::faceOf(c[i].triangle);
        if (!paired) {
            // Its exit lies past the horizon: given early only for the first span, begun
            // more than the margin past `from` (not one the ray starts inside).
            if (c[i].t <= past || out.count > 0) return wholeListNeeded();
            out.add(c[i].t, faceIn, horizon, kClipFace);
            return true;
        }
        out.add(c[i].t, faceIn, c[i + 1].t, Polyhedron::faceOf(c[i + 1].triangle));
        if (c[i + 1].t - std::max(c[i].t, out.from) > out.margin) return true;
    }
    // No span begins before the horizon, `to` + margin, where the caller clips; or the last
    // one is short and the next lies past the horizon.
    return out.count == 0 || wholeListNeeded();
}

}  // namespace

void Polyhedron::crossings(const Vec3& o, const Vec3& d, std::vector<Crossing>& out) const {
    out.clear();
    if (!data || data->invalid) return;
    // Start the line at its entry into the box (widened), as csg/ does for spans().
    double t0 = -kInfinity, t1 = kInfinity;
    if (!clipToBox(SlabRay(o, d), data->box, t0, t1)) return;
    const double shift = std::isfinite(t0) ? t0 : 0.0;
    collectCrossings(*data, pointOnLine(o, d, shift), d, out);
    for (Crossing& c : out) c.t += shift;
    sortCrossings(out);
}

void Polyhedron::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    if (!data || data->invalid) return;
    // (Only the watertight test pairs every line's crossings of a closed mesh.)
    if (out.firstOnly && method == PolygonMethod::Watertight && data->edges.closed() &&
        firstSpanOfClosedMesh(*data, structure.get(), method, o, d, out))
        return;
    std::vector<Crossing>& c = lineCrossings;
    c.clear();
    collectCrossings(*data, o, d, c, method, structure.get());
    if (c.size() < 2) return;
    sortCrossings(c);
    // Step 1: pairs; an odd count (an open mesh) loses its last crossing; touches (a ray
    // grazing an edge, coincident faces) are not spans.
    size_t pairs = 0;
    for (size_t i = 0; i + 1 < c.size(); i += 2)
        if (c[i].t < c[i + 1].t) c[2 * pairs] = c[i], c[2 * pairs + 1] = c[i + 1], ++pairs;
    // Step 2: more spans than LocalSpans holds: close the narrowest gaps (see Polyhedron.h).
    std::vector<LocalSpans::Entry>& spans = lineSpans;
    spans.clear();
    for (size_t i = 0; i < pairs; ++i)
        spans.push_back({c[2 * i].t, c[2 * i + 1].t, Polyhedron::faceOf(c[2 * i].triangle),
                         Polyhedron::faceOf(c[2 * i + 1].triangle)});
    addWithinCapacity(spans, out);
}

bool Polyhedron::inside(const Vec3& p) const {
    if (!data || data->invalid || !data->box.contains(p)) return false;
    std::vector<Crossing>& c = lineCrossings;
    c.clear();
    collectCrossings(*data, p, kInsideDirection, c);
    size_t ahead = 0;
    for (const Crossing& x : c) ahead += x.t > 0.0;
    return ahead % 2 == 1;
}

namespace {

Vec3 unitOr(const Vec3& v, const Vec3& fallback) {
    const double length = glm::length(v);
    return length > 0.0 && std::isfinite(length) ? v / length : fallback;
}

// Each triangle's corner normals (Polyhedron.h): at each corner, the normals of the triangles
// around that vertex within kSmoothCreaseDegrees of this one's, weighted by their angles there.
void buildCornerNormals(const PolyhedronData& mesh) {
    const size_t n = mesh.triangles.size();
    std::vector<Vec3> unit(n);
    // Each (vertex, triangle, corner) use, grouped by vertex.
    std::vector<uint32_t> start(mesh.vertices.size() + 1, 0);
    for (size_t i = 0; i < n; ++i) {
        const auto& t = mesh.triangles[i];
        const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        unit[i] = unitOr(glm::cross(b - a, c - a), Vec3(0.0));
        for (const uint32_t v : t) ++start[v + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<uint32_t> around(3 * n), fill(start.begin(), start.end() - 1);
    for (uint32_t i = 0; i < n; ++i)
        for (const uint32_t v : mesh.triangles[i]) around[fill[v]++] = i;
    // The triangle's angle at corner k.
    const auto angleAt = [&](uint32_t i, int k) {
        const auto& t = mesh.triangles[i];
        const Vec3& p = mesh.vertices[t[size_t(k)]];
        const Vec3 e1 = mesh.vertices[t[size_t(k + 1) % 3]] - p;
        const Vec3 e2 = mesh.vertices[t[size_t(k + 2) % 3]] - p;
        return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
    };
    const double crease = std::cos(kSmoothCreaseDegrees * std::numbers::pi / 180.0);
    mesh.cornerNormals.resize(n);
    for (uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = mesh.triangles[i][size_t(k)];
            Vec3 sum(0.0);
            for (uint32_t u = start[v]; u < start[v + 1]; ++u) {
                const uint32_t j = around[u];
                if (glm::dot(unit[j], unit[i]) < crease) continue;
                const auto& tj = mesh.triangles[j];
                const int corner = tj[0] == v ? 0 : tj[1] == v ? 1 : 2;
                sum += angleAt(j, corner) * unit[j];
            }
            mesh.cornerNormals[i][size_t(k)] = unitOr(sum, unit[i]);
        }
}

}  // namespace

Vec3 Polyhedron::normal(const Vec3& p, uint16_t face) const {
    if (!data || data->invalid || face >= data->triangles.size()) return Vec3(0.0, 0.0, 1.0);
    const auto corners = [&](uint32_t i) {
        const std::array<uint32_t, 3>& t = data->triangles[i];
        return std::array<Vec3, 3>{data->vertices[t[0]], data->vertices[t[1]],
                                   data->vertices[t[2]]};
    };
    // Step 1: the triangle of that residue nearest p (the only one below 65536 triangles).
    uint32_t best = face;
    if (data->triangles.size() > kFaceIds) {
        double bestDistance = kInfinity;
        for (size_t i = face; i < data->triangles.size(); i += kFaceIds) {
            const auto v = corners(uint32_t(i));
            const Vec3 gap = closestPointOnTriangle(p, v[0], v[1], v[2]) - p;
            const double distance = glm::dot(gap, gap);
            if (distance < bestDistance) bestDistance = distance, best = uint32_t(i);
        }
    }
    // Step 2: its plane's unit normal (triangles are wound outward).
    const auto v = corners(best);
    const Vec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const Vec3 flat = unitOr(n, Vec3(0.0, 0.0, 1.0));
    if (method == PolygonMethod::Watertight) return flat;
    // Step 3: the interpolating methods' weights of p's projection on the plane.
    const DroppedAxis axis(n);
    std::array<double, 3> b;
    if (method == PolygonMethod::Snyder) {
        b = snyderWeights(axis.of(v[0]), axis.of(v[1]), axis.of(v[2]), axis.of(p), n[axis.i0]);
    } else {
        const Vec2 origin = axis.of(v[0]);
        const std::optional<MarchalPoint> m =
            marchalPoint(axis.of(v[1]) - origin, axis.of(v[2]) - origin, axis.of(p) - origin);
        if (!m) return flat;  // p at P0, or off the triangle (a point on its edge P0 P1)
        b = {1.0 - m->r, m->r * (1.0 - m->s), m->r * m->s};
    }
    std::call_once(data->smoothOnce, [&] { buildCornerNormals(*data); });
    const std::array<Vec3, 3>& corner = data->cornerNormals[best];
    return unitOr(b[0] * corner[0] + b[1] * corner[1] + b[2] * corner[2], flat);
}

std::optional<PolygonMethod> parsePolygonMethod(std::string_view name) {
    for (size_t i = 0; i < kPolygonMethodNames.size(); ++i)
        if (kPolygonMethodNames[i] == name) return static_cast<PolygonMethod>(i);
    return std::nullopt;
}

}  // namespace csg
