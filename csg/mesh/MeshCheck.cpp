#include "csg/mesh/MeshCheck.h"

#include <algorithm>
#include <map>
#include <unordered_map>

namespace csg {

MeshTopology checkTopology(const TriangleMesh& mesh) {
    MeshTopology topo;

    // Step 1: every directed edge as (min, max, direction, triangle), sorted to group them.
    struct DirectedEdge {
        uint32_t lo, hi;
        bool forward;  // lo -> hi in the triangle's winding
        bool operator<(const DirectedEdge& o) const {
            return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : forward < o.forward;
        }
    };
    std::vector<DirectedEdge> edges;
    edges.reserve(mesh.triangles.size() * 3);
    for (const auto& tri : mesh.triangles) {
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
            ++topo.degenerateTriangles;
            continue;
        }
        for (int i = 0; i < 3; ++i) {
            const uint32_t p = tri[size_t(i)], q = tri[size_t((i + 1) % 3)];
            edges.push_back({std::min(p, q), std::max(p, q), p < q});
        }
    }
    std::sort(edges.begin(), edges.end());

    // Step 2: classify each undirected edge by its uses.
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        int forward = 0;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi)
            forward += edges[j++].forward;
        const size_t uses = j - i;
        ++topo.edges;
        if (uses == 1)
            ++topo.boundaryEdges;
        else if (uses > 2)
            ++topo.nonManifoldEdges;
        else if (forward != 1)
            ++topo.misorientedEdges;
        i = j;
    }

    // Step 3: a vertex is a disk when the edges opposite it in its triangles form one chain:
    // walk the fan by the "next" map and check that it reaches every triangle of the vertex.
    std::vector<uint32_t> start(mesh.positions.size() + 1, 0);
    for (const auto& tri : mesh.triangles)
        for (const uint32_t v : tri) ++start[v + 1];
    for (size_t v = 0; v < mesh.positions.size(); ++v) start[v + 1] += start[v];
    std::vector<std::pair<uint32_t, uint32_t>> opposite(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& tri : mesh.triangles)
        for (int i = 0; i < 3; ++i)
            opposite[fill[tri[size_t(i)]]++] = {tri[size_t((i + 1) % 3)], tri[size_t((i + 2) % 3)]};
    std::unordered_map<uint32_t, uint32_t> next;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const uint32_t count = start[v + 1] - start[v];
        if (count == 0) continue;
        next.clear();
        bool bad = false;
        for (uint32_t i = start[v]; i < start[v + 1]; ++i)
            bad |= !next.emplace(opposite[i].first, opposite[i].second).second;
        if (bad) {
            ++topo.nonManifoldVertices;
            continue;
        }
        // Walk from the first triangle; on an open fan (a boundary) the walk ends early too,
        // which boundaryEdges already reports, so only closed vertices are judged here.
        uint32_t steps = 0, at = opposite[start[v]].first;
        do {
            auto it = next.find(at);
            if (it == next.end()) break;
            at = it->second;
            ++steps;
        } while (at != opposite[start[v]].first && steps <= count);
        if (at == opposite[start[v]].first && steps != count) ++topo.nonManifoldVertices;
    }
    return topo;
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
    std::map<std::array<double, 3>, uint32_t> index;
    std::vector<uint32_t> remap(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3& p = mesh.positions[i];
        const auto [it, added] =
            index.emplace(std::array<double, 3>{p.x, p.y, p.z}, uint32_t(out.positions.size()));
        if (added) {
            out.positions.push_back(p);
            if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[i]);
        }
        remap[i] = it->second;
    }
    out.triangles.reserve(mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
        out.triangles.push_back({remap[tri[0]], remap[tri[1]], remap[tri[2]]});
    out.triangleMaterial = mesh.triangleMaterial;
    return out;
}

}  // namespace csg
