#include "csg/mesh/MeshCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "csg/mesh/TriangleBvh.h"
#include "primitives/base/GroupByKey.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/PointWelder.h"
#include "primitives/base/Tolerances.h"

namespace csg {

MeshTopology checkTopology(const TriangleMesh& mesh) {
    MeshTopology topo;

    // Step 1: the corners of each vertex, grouped by vertex (groupByKey): per corner, the
    // vertex after it and the one before it in its triangle's winding, and whether the triangle
    // repeats a corner (it then takes part in the fan walk of step 3 but has no edges).
    struct Corner {
        uint32_t next, prev;
        bool degenerate;
    };
    const auto repeatsCorner = [](const std::array<uint32_t, 3>& tri) {
        return tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
    };
    Grouped<Corner> byVertex = groupByKey<Corner>(mesh.positions.size(), [&](auto emit) {
        for (const auto& tri : mesh.triangles) {
            const bool degenerate = repeatsCorner(tri);
            for (int i = 0; i < 3; ++i)
                emit(tri[size_t(i)],
                     Corner{tri[size_t((i + 1) % 3)], tri[size_t((i + 2) % 3)], degenerate});
        }
    });
    const std::vector<uint32_t>& start = byVertex.start;
    std::vector<Corner>& corners = byVertex.values;
    for (const auto& tri : mesh.triangles) topo.degenerateTriangles += repeatsCorner(tri);

    // Per vertex, sorts of its own corners only, so the work is T log(valence), also where a
    // loaded mesh has a vertex of very high valence (a cone's apex).
    struct End {
        uint32_t w;
        bool forward;
    };
    std::vector<End> ends;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const uint32_t first = start[v], last = start[v + 1];
        if (first == last) continue;

        // Step 2: classify each undirected edge {v, w} with w > v by its uses in the corners
        // of v: v -> w (a corner's next) runs it forward, w -> v (its prev) backward.
        ends.clear();
        for (uint32_t i = first; i < last; ++i) {
            if (corners[i].degenerate) continue;
            ends.push_back({corners[i].next, true});
            ends.push_back({corners[i].prev, false});
        }
        std::sort(ends.begin(), ends.end(), [](const End& a, const End& b) { return a.w < b.w; });
        for (size_t i = 0; i < ends.size();) {
            size_t k = i;
            uint32_t forward = 0;
            for (; k < ends.size() && ends[k].w == ends[i].w; ++k) forward += ends[k].forward;
            const size_t uses = k - i;
            if (ends[i].w > v) {
                ++topo.edges;
                if (uses == 1)
                    ++topo.boundaryEdges;
                else if (uses > 2)
                    ++topo.nonManifoldEdges;
                else if (forward != 1)
                    ++topo.misorientedEdges;
            }
            i = k;
        }

        // Step 3: v is a disk when the edges opposite it in its triangles form one chain: walk
        // the fan from next to prev and check that it reaches every triangle of the vertex.
        // Two corners leaving from the same next vertex make the walk ambiguous: not a disk.
        // The walk starts at v's first corner in triangle order (on a messy fan the verdict
        // can depend on where it starts), then the corners are sorted for the lookups.
        const uint32_t begin = corners[first].next;
        const auto byNext = [](const Corner& a, const Corner& b) { return a.next < b.next; };
        std::sort(corners.begin() + first, corners.begin() + last, byNext);
        const uint32_t count = last - first;
        bool bad = false;
        for (uint32_t i = first + 1; i < last && !bad; ++i)
            bad = corners[i - 1].next == corners[i].next;
        if (bad) {
            ++topo.nonManifoldVertices;
            continue;
        }
        // On an open fan (a boundary) the walk ends early too,
        // which boundaryEdges already reports, so only closed vertices are judged here.
        auto after = [&](uint32_t at) -> const Corner* {
            const auto it = std::lower_bound(corners.begin() + first, corners.begin() + last,
                                             Corner{at, 0, false}, byNext);
            return it != corners.begin() + last && it->next == at ? &*it : nullptr;
        };
        uint32_t steps = 0, at = begin;
        do {
            const Corner* c = after(at);
            if (!c) break;
            at = c->prev;
            ++steps;
        } while (at != begin && steps <= count);
        if (at == begin && steps != count) ++topo.nonManifoldVertices;
    }
    return topo;
}

namespace {

using Tri = ContactTriangle;

// Whether the interiors of coplanar triangles a and b overlap by more than tol, in a's plane:
// they do unless an edge line of one has the other's corners all on its outer side or within
// tol of it (the separating axis theorem for two convex polygons). Writes a point of the
// overlap to where (the centroid of a clipped by b).
bool coplanarOverlap(const Tri& a, const Tri& b, double tol, Vec3* where) {
    // Orthonormal frame of a's plane.
    const Vec3 u = glm::normalize(a.p[1] - a.p[0]);
    const Vec3 w = glm::cross(a.n, u);
    auto flat = [&](const Vec3& q) {
        const Vec3 d = q - a.p[0];
        return glm::dvec2(glm::dot(d, u), glm::dot(d, w));
    };
    glm::dvec2 pa[3], pb[3];
    for (int i = 0; i < 3; ++i) pa[i] = flat(a.p[i]), pb[i] = flat(b.p[i]);
    auto separates = [tol](const glm::dvec2* t, const glm::dvec2* other) {
        for (int i = 0; i < 3; ++i) {
            const glm::dvec2 p = t[i], e = t[(i + 1) % 3] - p;
            const double len = glm::length(e);
            if (!(len > 0.0)) continue;
            glm::dvec2 inward(-e.y / len, e.x / len);
            if (glm::dot(t[(i + 2) % 3] - p, inward) < 0.0) inward = -inward;
            bool allOutside = true;
            for (int k = 0; k < 3 && allOutside; ++k)
                allOutside = glm::dot(other[k] - p, inward) <= tol;
            if (allOutside) return true;
        }
        return false;
    };
    if (separates(pa, pb) || separates(pb, pa)) return false;
    // Clip a by b's three inner half-planes (Sutherland-Hodgman) for a point of the overlap.
    std::vector<glm::dvec2> poly(pa, pa + 3), next;
    for (int i = 0; i < 3 && !poly.empty(); ++i) {
        const glm::dvec2 p = pb[i], e = pb[(i + 1) % 3] - p;
        glm::dvec2 inward(-e.y, e.x);
        if (glm::dot(pb[(i + 2) % 3] - p, inward) < 0.0) inward = -inward;
        next.clear();
        for (size_t k = 0; k < poly.size(); ++k) {
            const glm::dvec2 s = poly[k], f = poly[(k + 1) % poly.size()];
            const double ds = glm::dot(s - p, inward), df = glm::dot(f - p, inward);
            if (ds >= 0.0) next.push_back(s);
            if ((ds < 0.0) != (df < 0.0)) next.push_back(s + (f - s) * (ds / (ds - df)));
        }
        poly.swap(next);
    }
    glm::dvec2 c(0.0);
    for (const glm::dvec2& q : poly) c += q;
    if (!poly.empty()) c /= double(poly.size());
    *where = a.p[0] + c.x * u + c.y * w;
    return true;
}

// The points where triangle t meets the other triangle's plane, given the signed distances d
// of its corners from it: corners on the plane and crossings of
// edges whose ends lie strictly on opposite sides. Returns their count (0 to 3).
int pointsOnPlane(const Tri& t, const double d[3], Vec3 out[3]) {
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        if (d[i] == 0.0) out[count++] = t.p[i];
        if ((d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0))
            if (count < 3) out[count++] = t.p[i] + (t.p[j] - t.p[i]) * (d[i] / (d[i] - d[j]));
    }
    return count;
}

using Contact = TriangleContact;

// Whether triangles a and b intersect other than at what they share (see
// findSelfIntersections), and how; writes a point of the intersection to where.
Contact trianglesCross(const Tri& a, const Tri& b, double tol, double flatTol, Vec3* where) {
    // Shared corners: bit-identical positions.
    int shared = 0;
    bool aShared[3] = {false, false, false}, bShared[3] = {false, false, false};
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
            if (a.p[i] == b.p[k]) {
                shared += !aShared[i];
                aShared[i] = bShared[k] = true;
            }
    // Signed distances of each triangle's corners from the other's plane (exactly zero for a
    // shared corner, which lies in both planes). A triangle whose corners all lie within tol of
    // the other's plane is coplanar with it. Otherwise the distances keep their rounded signs:
    // zeroing the small ones would let a near-parallel pair, each with an edge within tol of
    // the other's plane, appear to meet along those edges, projected onto a line their planes
    // barely define; a contact that rounding turns into a crossing gives a segment shorter
    // than tol below instead.
    double da[3], db[3];
    bool aFlat = true, bFlat = true;
    for (int i = 0; i < 3; ++i) {
        da[i] = aShared[i] ? 0.0 : glm::dot(a.p[i] - b.p[0], b.n);
        db[i] = bShared[i] ? 0.0 : glm::dot(b.p[i] - a.p[0], a.n);
        aFlat &= std::abs(da[i]) <= flatTol;
        bFlat &= std::abs(db[i]) <= flatTol;
    }
    if (aFlat || bFlat)
        return coplanarOverlap(a, b, tol, where) ? Contact::Coplanar : Contact::None;
    // A crossing goes deeper than tol: each triangle has corners more than tol beyond the
    // other's plane on both sides. A shallower pair is a contact that rounding may have pushed
    // through: at a small angle between the planes, a corner 1e-7 through (a GLB's rounding)
    // makes an overlap segment 1e-7 / sin(angle) long, longer than tol, so the segment's
    // length alone does not tell them apart.
    auto straddles = [tol](const double d[3]) {
        return std::max({d[0], d[1], d[2]}) > tol && std::min({d[0], d[1], d[2]}) < -tol;
    };
    if (!straddles(da) || !straddles(db)) return Contact::None;
    // Not coplanar, sharing an edge: they meet along it only.
    if (shared >= 2) return Contact::None;
    // Moeller: each triangle meets the other's plane in a segment on the line where the planes
    // meet; the triangles cross where the two segments overlap.
    Vec3 pa[3], pb[3];
    const int na = pointsOnPlane(a, da, pa), nb = pointsOnPlane(b, db, pb);
    if (na == 0 || nb == 0) return Contact::None;
    const Vec3 dir = glm::normalize(glm::cross(a.n, b.n));
    auto span = [&](const Vec3* p, int n, double& lo, double& hi, Vec3& pLo, Vec3& pHi) {
        lo = std::numeric_limits<double>::infinity();
        hi = -lo;
        for (int i = 0; i < n; ++i) {
            const double s = glm::dot(p[i], dir);
            if (s < lo) lo = s, pLo = p[i];
            if (s > hi) hi = s, pHi = p[i];
        }
    };
    double loA, hiA, loB, hiB;
    Vec3 aLo(0.0), aHi(0.0), bLo(0.0), bHi(0.0);
    span(pa, na, loA, hiA, aLo, aHi);
    span(pb, nb, loB, hiB, bLo, bHi);
    const double lo = std::max(loA, loB), hi = std::min(hiA, hiB);
    if (!(hi - lo > tol)) return Contact::None;
    const double mid = 0.5 * (lo + hi);
    *where = aLo + (aHi - aLo) * ((mid - loA) / (hiA - loA));
    return Contact::Crossing;
}

}  // namespace

double selfIntersectionTolerance(const TriangleMesh& mesh, double contactRel) {
    double scale = 0.0;
    for (const Vec3& p : mesh.positions)
        scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return contactRel * scale;
}

ContactTriangle contactTriangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, double tol) {
    ContactTriangle t{{p0, p1, p2}, Vec3(0.0)};
    const Vec3 c = glm::cross(p1 - p0, p2 - p0);
    const double twiceArea = glm::length(c);
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, glm::length(t.p[(k + 1) % 3] - t.p[k]));
    // Height over the longest edge: a triangle thinner than tol has no reliable plane.
    if (twiceArea > tol * longest && twiceArea > 0.0) t.n = c / twiceArea;
    return t;
}

TriangleContact triangleContact(const ContactTriangle& a, const ContactTriangle& b, double tol,
                                double flatTol) {
    if (a.n == Vec3(0.0) || b.n == Vec3(0.0)) return Contact::None;
    Vec3 where;
    return trianglesCross(a, b, tol, flatTol, &where);
}

SelfIntersections findSelfIntersections(const TriangleMesh& mesh, double contactRel, int threads) {
    if (mesh.triangles.size() < 2) return {};
    const TriangleBvh bvh(mesh, threads);
    return findSelfIntersections(mesh, bvh, contactRel, threads);
}

SelfIntersections findSelfIntersections(const TriangleMesh& mesh, const TriangleBvh& bvh,
                                        double contactRel, int threads) {
    SelfIntersections result;
    const size_t n = mesh.triangles.size();
    if (n < 2) return result;
    const double tol = selfIntersectionTolerance(mesh, contactRel);

    std::vector<Tri> tris(n);
    for (size_t i = 0; i < n; ++i) {
        const auto& tri = mesh.triangles[i];
        tris[i] = contactTriangle(mesh.positions[tri[0]], mesh.positions[tri[1]],
                                  mesh.positions[tri[2]], tol);
        result.skippedSlivers += tris[i].n == Vec3(0.0);
    }

    // Per worker: its count and the first pair (in triangle order) it found.
    struct Found {
        uint64_t pairs = 0, coplanar = 0;
        uint32_t a = UINT32_MAX, b = UINT32_MAX;
        Vec3 where{0.0};
    };
    const int workers = resolveThreads(threads);
    std::vector<Found> found(static_cast<size_t>(workers));
    constexpr uint64_t kChunk = 1024;
    parallelFor((n + kChunk - 1) / kChunk, workers, [&](int worker, uint64_t chunk) {
        Found& f = found[size_t(worker)];
        for (size_t i = chunk * kChunk; i < std::min<size_t>(n, (chunk + 1) * kChunk); ++i) {
            const Tri& a = tris[i];
            if (a.n == Vec3(0.0)) continue;
            Bounds3 box;
            for (const Vec3& p : a.p) box.extend(p);
            box.lo -= Vec3(tol);
            box.hi += Vec3(tol);
            bvh.forEachOverlapping(box, [&](uint32_t j) {
                if (j <= i || tris[j].n == Vec3(0.0)) return;
                Vec3 where;
                const Contact contact = trianglesCross(a, tris[j], tol, tol, &where);
                if (contact == Contact::None) return;
                ++f.pairs;
                f.coplanar += contact == Contact::Coplanar;
                if (uint32_t(i) < f.a || (uint32_t(i) == f.a && j < f.b))
                    f = {f.pairs, f.coplanar, uint32_t(i), j, where};
            });
        }
    });
    uint32_t bestA = UINT32_MAX, bestB = UINT32_MAX;
    for (const Found& f : found) {
        result.pairs += f.pairs;
        result.coplanarPairs += f.coplanar;
        if (f.pairs > 0 && (f.a < bestA || (f.a == bestA && f.b < bestB))) {
            bestA = f.a, bestB = f.b;
            result.example = f.where;
            result.exampleA = f.a, result.exampleB = f.b;
        }
    }
    return result;
}

SelfIntersections findSelfIntersections(const TriangleMesh& mesh) {
    return findSelfIntersections(mesh, tol::kSelfIntersectionContactRel);
}

double signedVolume(const TriangleMesh& mesh) {
    if (mesh.positions.empty()) return 0.0;
    // Relative to the first vertex of the mesh: smaller terms, less cancellation far away.
    const Vec3 o = mesh.positions[0];
    double total = 0.0;
    for (const auto& tri : mesh.triangles)
        total += glm::dot(mesh.positions[tri[0]] - o,
                          glm::cross(mesh.positions[tri[1]] - o, mesh.positions[tri[2]] - o));
    return total / 6.0;
}

double surfaceArea(const TriangleMesh& mesh) {
    double total = 0.0;
    for (const auto& tri : mesh.triangles)
        total += 0.5 * glm::length(glm::cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                                              mesh.positions[tri[2]] - mesh.positions[tri[0]]));
    return total;
}

TriangleMesh weldExactDuplicates(const TriangleMesh& mesh) {
    TriangleMesh out;
    PointWelder welder(mesh.positions.size());
    std::vector<uint32_t> remap(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const size_t before = welder.size();
        remap[i] = welder.add(mesh.positions[i]);
        if (welder.size() > before && !mesh.normals.empty()) out.normals.push_back(mesh.normals[i]);
    }
    out.positions = welder.take();
    out.triangles.reserve(mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
        out.triangles.push_back({remap[tri[0]], remap[tri[1]], remap[tri[2]]});
    out.triangleMaterial = mesh.triangleMaterial;
    return out;
}

}  // namespace csg
