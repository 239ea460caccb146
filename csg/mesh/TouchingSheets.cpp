#include "csg/mesh/TouchingSheets.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include "csg/mesh/MeshCheck.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// Disjoint sets over the mesh's corners (corner 3 t + k: corner k of triangle t).
struct CornerSets {
    std::vector<uint32_t> parent;

    explicit CornerSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t c) {
        while (parent[c] != c) c = parent[c] = parent[parent[c]];
        return c;
    }
    void join(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

// The corner of triangle t that holds vertex v (t holds it).
uint32_t cornerOf(const TriangleMesh& mesh, uint32_t t, uint32_t v) {
    const auto& tri = mesh.triangles[t];
    return 3 * t + (tri[0] == v ? 0u : tri[1] == v ? 1u : 2u);
}

// Pairs the half-edges hs (all on the edge p-q, p < q, more than two) by their order around
// the edge: a half-edge running q -> p has the solid on the side of increasing angle (its
// outward normal, (q - p) x (r - p) reversed, points back), one running p -> q on the side of
// decreasing angle, so a solid wedge runs from a q -> p half-edge to the next one in angle,
// which must run p -> q. False when they do not alternate so, when a triangle has no width
// across the edge, or when two neighbours around it are closer than
// tol::kTouchingSheetsMinWedge (a face folded onto another, not a contact).
bool pairAroundEdge(const TriangleMesh& mesh, uint32_t p, uint32_t q,
                    const std::vector<uint32_t>& hs, std::vector<uint32_t>& partner) {
    const Vec3 origin = mesh.positions[p];
    const Vec3 axis = mesh.positions[q] - origin;
    const double length = glm::length(axis);
    if (!(length > 0.0)) return false;
    const Vec3 u = axis / length;
    struct Around {
        double angle;
        uint32_t halfEdge;
        bool forward;  // runs p -> q
    };
    std::vector<Around> around;
    Vec3 v1(0.0), v2(0.0);
    for (const uint32_t h : hs) {
        const auto& tri = mesh.triangles[h / 3];
        const uint32_t k = h % 3;
        const Vec3 r = mesh.positions[tri[(k + 2) % 3]] - origin;
        const Vec3 w = r - u * glm::dot(r, u);
        const double width = glm::length(w);
        if (!(width > 0.0)) return false;
        if (around.empty()) {
            v1 = w / width;
            v2 = glm::cross(u, v1);
        }
        around.push_back({std::atan2(glm::dot(w, v2), glm::dot(w, v1)), h, tri[k] == p});
    }
    std::sort(around.begin(), around.end(),
              [](const Around& a, const Around& b) { return a.angle < b.angle; });
    const size_t n = around.size();
    constexpr double kTurn = 2.0 * std::numbers::pi;
    for (size_t i = 0; i < n; ++i) {
        const double wedge = i + 1 < n ? around[i + 1].angle - around[i].angle
                                       : around[0].angle + kTurn - around[i].angle;
        if (!(wedge > tol::kTouchingSheetsMinWedge)) return false;
    }
    for (size_t i = 0; i < n; ++i) {
        if (around[i].forward) continue;
        const Around& next = around[(i + 1) % n];
        if (!next.forward) return false;
        partner[around[i].halfEdge] = next.halfEdge;
        partner[next.halfEdge] = around[i].halfEdge;
    }
    for (const Around& a : around)
        if (partner[a.halfEdge] == kNone) return false;
    return true;
}

}  // namespace

uint64_t separateTouchingSheets(TriangleMesh& mesh) {
    const size_t corners = 3 * mesh.triangles.size();
    if (corners == 0 || corners >= kNone) return 0;
    // A triangle that repeats a corner is a defect, not a contact: left for checkTopology.
    for (const auto& tri : mesh.triangles)
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) return 0;

    // Step 1: the half-edges grouped by undirected edge.
    const auto edgeOf = [&](uint32_t h) {
        const auto& tri = mesh.triangles[h / 3];
        const uint32_t a = tri[h % 3], b = tri[(h % 3 + 1) % 3];
        return std::pair(std::min(a, b), std::max(a, b));
    };
    std::vector<uint32_t> order(corners);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return edgeOf(a) < edgeOf(b); });

    // Step 2: each half-edge's partner across its edge, and the corners the pairing joins: the
    // two ends of a half-edge are the same vertex fan as the matching ends of its partner. An
    // edge whose half-edges cannot be paired keeps all their corners in one fan at each end.
    std::vector<uint32_t> partner(corners, kNone);
    CornerSets fans(corners);
    std::vector<uint32_t> group;
    for (size_t i = 0; i < corners;) {
        size_t j = i + 1;
        while (j < corners && edgeOf(order[j]) == edgeOf(order[i])) ++j;
        group.assign(order.begin() + long(i), order.begin() + long(j));
        const auto [p, q] = edgeOf(order[i]);
        i = j;
        if (group.size() == 2) {
            partner[group[0]] = group[1], partner[group[1]] = group[0];
        } else if (group.size() < 2 || group.size() % 2 != 0 ||
                   !pairAroundEdge(mesh, p, q, group, partner)) {
            for (const uint32_t h : group) {
                partner[h] = kNone;
                fans.join(cornerOf(mesh, h / 3, p), cornerOf(mesh, group[0] / 3, p));
                fans.join(cornerOf(mesh, h / 3, q), cornerOf(mesh, group[0] / 3, q));
            }
            continue;
        }
        for (const uint32_t h : group) {
            const uint32_t other = partner[h] / 3;
            fans.join(cornerOf(mesh, h / 3, p), cornerOf(mesh, other, p));
            fans.join(cornerOf(mesh, h / 3, q), cornerOf(mesh, other, q));
        }
    }

    // Step 3: one vertex per fan; a vertex's first fan keeps its index.
    std::vector<uint32_t> vertexOfFan(corners, kNone), firstFan(mesh.positions.size(), kNone);
    uint64_t added = 0;
    for (uint32_t c = 0; c < corners; ++c) {
        uint32_t& v = mesh.triangles[c / 3][c % 3];
        const uint32_t fan = fans.find(c);
        if (vertexOfFan[fan] == kNone) {
            if (firstFan[v] == kNone) {
                firstFan[v] = fan;
                vertexOfFan[fan] = v;
            } else {
                vertexOfFan[fan] = uint32_t(mesh.positions.size());
                mesh.positions.push_back(mesh.positions[v]);
                if (!mesh.normals.empty()) mesh.normals.push_back(mesh.normals[v]);
                ++added;
            }
        }
        v = vertexOfFan[fan];
    }
    return added;
}

bool closedOnceSheetsSeparated(TriangleMesh& mesh) {
    return checkTopology(mesh).closedManifold() ||
           (separateTouchingSheets(mesh) > 0 && checkTopology(mesh).closedManifold());
}

}  // namespace csg
