#include "csg/mesh/CoplanarMerge.h"

#include <algorithm>
#include <numeric>

#include "csg/mesh/EarClip.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

constexpr uint32_t kNone = UINT32_MAX;
// Ear clipping is quadratic in a face's corners (cubic at worst): a face with more than this many
// is not merged here, and the caller's simplifier does it. Measured: a plate face with 1 600
// holes of 16 corners (25 600 corners) took 6.5 s, one with 400 (6 400) 0.5 s.
constexpr size_t kMostCornersPerFace = 20000;

uint64_t edgeKey(uint32_t a, uint32_t b) {
    return (uint64_t(a) << 32) | b;
}

class UnionFind {
public:
    explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
    uint32_t find(uint32_t i) {
        while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
        return i;
    }
    void unite(uint32_t a, uint32_t b) {
        a = find(a), b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<uint32_t> parent_;
};

double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 e = b - a;
    const double length2 = glm::dot(e, e);
    const double s = length2 > 0.0 ? std::clamp(glm::dot(p - a, e) / length2, 0.0, 1.0) : 0.0;
    return glm::distance(p, a + s * e);
}

// An outline loop of a face (the root polygon of its union-find set).
struct Loop {
    uint32_t face;
    std::vector<uint32_t> corners;
};

// Step 2: the outline loops of every face; false when an outline touches itself at a vertex.
bool outlineLoops(const std::vector<std::vector<uint32_t>>& polygons, UnionFind& faces,
                  const std::vector<std::pair<uint64_t, uint32_t>>& edges, std::vector<Loop>& out) {
    // Outline edges, sorted by face and then by first vertex.
    struct Outline {
        uint32_t face, a, b;
        bool operator<(const Outline& o) const { return face != o.face ? face < o.face : a < o.a; }
    };
    std::vector<Outline> outline;
    for (uint32_t p = 0; p < polygons.size(); ++p) {
        const auto& poly = polygons[p];
        for (size_t i = 0, k = poly.size(); i < k; ++i) {
            const uint32_t a = poly[i], b = poly[(i + 1) % k];
            const auto twin = std::lower_bound(edges.begin(), edges.end(),
                                               std::pair<uint64_t, uint32_t>{edgeKey(b, a), 0});
            if (faces.find(twin->second) != faces.find(p)) outline.push_back({faces.find(p), a, b});
        }
    }
    std::sort(outline.begin(), outline.end());
    std::vector<uint8_t> used(outline.size(), 0);
    for (size_t begin = 0; begin < outline.size();) {
        size_t end = begin;
        while (end < outline.size() && outline[end].face == outline[begin].face) ++end;
        for (size_t i = begin; i + 1 < end; ++i)
            if (outline[i].a == outline[i + 1].a) return false;  // a vertex the face pinches
        const auto from = [&](uint32_t v) {
            const auto it =
                std::lower_bound(outline.begin() + long(begin), outline.begin() + long(end),
                                 Outline{outline[begin].face, v, 0});
            return it != outline.begin() + long(end) && it->a == v ? size_t(it - outline.begin())
                                                                   : size_t(kNone);
        };
        for (size_t i = begin; i < end; ++i) {
            if (used[i]) continue;
            Loop loop{outline[begin].face, {}};
            size_t e = i;
            do {
                used[e] = 1;
                loop.corners.push_back(outline[e].a);
                e = from(outline[e].b);
                if (e == kNone) return false;
            } while (!used[e]);
            if (e != i) return false;
            out.push_back(std::move(loop));
        }
        begin = end;
    }
    return true;
}

// Step 3: which vertices stay, as a flag per position.
bool markCorners(const std::vector<Vec3>& positions, const std::vector<Loop>& loops,
                 double straight, std::vector<uint8_t>& corner) {
    corner.assign(positions.size(), 0);
    for (const Loop& loop : loops)
        for (size_t i = 0, k = loop.corners.size(); i < k; ++i) {
            const uint32_t u = loop.corners[(i + k - 1) % k], v = loop.corners[i],
                           w = loop.corners[(i + 1) % k];
            if (u == w || distanceToSegment(positions[v], positions[u], positions[w]) > straight)
                corner[v] = 1;
        }
    // Each vertex was checked against its own neighbours; a run of them may still bend away from
    // the segment between the corners around it. Its farthest vertex then stays, until none does.
    for (bool changed = true; changed;) {
        changed = false;
        for (const Loop& loop : loops) {
            const size_t k = loop.corners.size();
            size_t first = kNone;
            for (size_t i = 0; i < k && first == kNone; ++i)
                if (corner[loop.corners[i]]) first = i;
            if (first == kNone) return false;
            for (size_t i = first, done = 0; done < k;) {
                size_t j = (i + 1) % k, steps = 1;
                while (!corner[loop.corners[j]]) j = (j + 1) % k, ++steps;
                const Vec3 a = positions[loop.corners[i]], b = positions[loop.corners[j]];
                double farthest = straight;
                uint32_t keep = kNone;
                for (size_t m = (i + 1) % k; m != j; m = (m + 1) % k) {
                    const double d = distanceToSegment(positions[loop.corners[m]], a, b);
                    if (d > farthest) farthest = d, keep = loop.corners[m];
                }
                if (keep != kNone) corner[keep] = 1, changed = true;
                i = j, done += steps;
            }
        }
    }
    return true;
}

// Whether the point q lies inside the loop (crossing number, in the plane's coordinates).
bool insideLoop(const std::vector<Vec2>& points, const std::vector<uint32_t>& loop, Vec2 q) {
    bool inside = false;
    for (size_t i = 0, k = loop.size(); i < k; ++i) {
        const Vec2 a = points[loop[i]], b = points[loop[(i + 1) % k]];
        if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y))
            inside = !inside;
    }
    return inside;
}

// Step 4 for the loops of one face, in local indices into points (the face's plane coordinates,
// counter-clockwise seen from outside): each outer loop with the holes inside it.
bool triangulateFace(const std::vector<Vec2>& points,
                     const std::vector<std::vector<uint32_t>>& loops, double straight,
                     std::vector<std::array<uint32_t, 3>>& out) {
    std::vector<size_t> outers, holes;
    std::vector<double> areas;
    for (size_t i = 0; i < loops.size(); ++i) {
        areas.push_back(signedArea(points, loops[i]));
        (areas.back() > 0.0 ? outers : holes).push_back(i);
    }
    if (outers.empty()) return false;
    std::vector<std::vector<std::vector<uint32_t>>> holesOf(outers.size());
    for (const size_t h : holes) {
        // The smallest outer loop around the hole (one, unless the face has islands).
        size_t best = kNone;
        for (size_t o = 0; o < outers.size(); ++o)
            if ((outers.size() == 1 || insideLoop(points, loops[outers[o]], points[loops[h][0]])) &&
                (best == kNone || areas[outers[o]] < areas[outers[best]]))
                best = o;
        if (best == kNone) return false;
        holesOf[best].push_back(loops[h]);
    }
    for (size_t o = 0; o < outers.size(); ++o)
        if (!earClip(points, loops[outers[o]], holesOf[o], straight, out)) return false;
    return true;
}

}  // namespace

std::optional<TriangleMesh> mergeCoplanar(const std::vector<Vec3>& positions,
                                          const std::vector<std::vector<uint32_t>>& polygons,
                                          const std::vector<Vec3>& normals,
                                          const std::vector<uint32_t>& materials, double straight) {
    // Step 1: every directed edge once, with its polygon; pieces joined across shared edges.
    std::vector<std::pair<uint64_t, uint32_t>> edges;
    for (uint32_t p = 0; p < polygons.size(); ++p)
        for (size_t i = 0, k = polygons[p].size(); i < k; ++i)
            edges.push_back({edgeKey(polygons[p][i], polygons[p][(i + 1) % k]), p});
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i + 1 < edges.size(); ++i)
        if (edges[i].first == edges[i + 1].first) return std::nullopt;
    UnionFind faces(polygons.size());
    for (const auto& [key, p] : edges) {
        const uint64_t reverse = (key << 32) | (key >> 32);
        const auto twin =
            std::lower_bound(edges.begin(), edges.end(), std::pair<uint64_t, uint32_t>{reverse, 0});
        if (twin == edges.end() || twin->first != reverse) return std::nullopt;
        const uint32_t q = twin->second;
        if (materials[p] == materials[q] &&
            glm::dot(normals[p], normals[q]) >= 1.0 - tol::kPolyBoundaryParallelCos)
            faces.unite(p, q);
    }

    std::vector<Loop> loops;
    if (!outlineLoops(polygons, faces, edges, loops)) return std::nullopt;
    std::vector<uint8_t> corner;
    if (!markCorners(positions, loops, straight, corner)) return std::nullopt;
    for (Loop& loop : loops) {
        std::erase_if(loop.corners, [&](uint32_t v) { return !corner[v]; });
        if (loop.corners.size() < 3) return std::nullopt;
    }
    std::stable_sort(loops.begin(), loops.end(),
                     [](const Loop& a, const Loop& b) { return a.face < b.face; });

    TriangleMesh mesh;
    std::vector<uint32_t> newIndex(positions.size(), kNone);
    std::vector<uint32_t> local(positions.size(), kNone);
    std::vector<uint32_t> globalOf;
    std::vector<Vec2> plane;
    std::vector<std::vector<uint32_t>> faceLoops;
    std::vector<std::array<uint32_t, 3>> triangles;
    for (size_t begin = 0; begin < loops.size();) {
        const uint32_t face = loops[begin].face;
        size_t end = begin;
        while (end < loops.size() && loops[end].face == face) ++end;
        // The face's plane coordinates: u, v with u x v = n, so counter-clockwise stays so.
        const Vec3 n = normals[face];
        const Vec3 axis = std::abs(n.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        const Vec3 u = glm::normalize(glm::cross(n, axis)), v = glm::cross(n, u);
        globalOf.clear(), plane.clear(), faceLoops.clear(), triangles.clear();
        for (size_t l = begin; l < end; ++l) {
            faceLoops.emplace_back();
            for (const uint32_t g : loops[l].corners) {
                if (local[g] == kNone) {
                    local[g] = uint32_t(globalOf.size());
                    globalOf.push_back(g);
                    plane.push_back({glm::dot(positions[g], u), glm::dot(positions[g], v)});
                }
                faceLoops.back().push_back(local[g]);
            }
        }
        for (const uint32_t g : globalOf) local[g] = kNone;
        if (globalOf.size() > kMostCornersPerFace ||
            !triangulateFace(plane, faceLoops, straight, triangles))
            return std::nullopt;
        for (const auto& t : triangles) {
            std::array<uint32_t, 3> out;
            for (int k = 0; k < 3; ++k) {
                const uint32_t g = globalOf[t[size_t(k)]];
                if (newIndex[g] == kNone) {
                    newIndex[g] = uint32_t(mesh.positions.size());
                    mesh.positions.push_back(positions[g]);
                }
                out[size_t(k)] = newIndex[g];
            }
            mesh.triangles.push_back(out);
            mesh.triangleMaterial.push_back(materials[face]);
        }
        begin = end;
    }
    return mesh;
}

}  // namespace csg
