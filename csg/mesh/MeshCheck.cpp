#include "csg/mesh/MeshCheck.h"

#include <algorithm>
#include <map>
#include <vector>

namespace csg {

MeshTopology checkTopology(const TriangleMesh& mesh) {
    MeshTopology topo;

    // Step 1: the corners of each vertex, grouped by vertex (counting sort): per corner, the
    // vertex after it and the one before it in its triangle's winding, and whether the triangle
    // repeats a corner (it then takes part in the fan walk of step 3 but has no edges).
    struct Corner {
        uint32_t next, prev;
        bool degenerate;
    };
    std::vector<uint32_t> start(mesh.positions.size() + 1, 0);
    for (const auto& tri : mesh.triangles)
        for (const uint32_t v : tri) ++start[v + 1];
    for (size_t v = 0; v < mesh.positions.size(); ++v) start[v + 1] += start[v];
    std::vector<Corner> corners(start.back());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& tri : mesh.triangles) {
        const bool degenerate = tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
        topo.degenerateTriangles += degenerate;
        for (int i = 0; i < 3; ++i)
            corners[fill[tri[size_t(i)]]++] = {tri[size_t((i + 1) % 3)], tri[size_t((i + 2) % 3)],
                                               degenerate};
    }

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
