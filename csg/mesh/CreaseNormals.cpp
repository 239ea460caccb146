#include "csg/mesh/CreaseNormals.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace csg {

TriangleMesh splitAtCreases(const TriangleMesh& mesh, double creaseDegrees) {
    const size_t vertexCount = mesh.positions.size(), triangleCount = mesh.triangles.size();
    const double minCos = std::cos(creaseDegrees * std::numbers::pi / 180.0);
    auto corner = [&](uint32_t t, uint32_t c) { return mesh.positions[mesh.triangles[t][c]]; };

    // Step 1: unit triangle normals (zero for a degenerate triangle).
    std::vector<Vec3> faceNormal(triangleCount);
    for (uint32_t t = 0; t < triangleCount; ++t) {
        const Vec3 n = glm::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0));
        const double len = glm::length(n);
        faceNormal[t] = len > 0.0 ? n / len : Vec3(0.0);
    }

    // Step 2: the corners around each vertex (t * 3 + c), grouped by vertex.
    std::vector<uint32_t> start(vertexCount + 1, 0), corners(3 * triangleCount);
    for (const auto& tri : mesh.triangles)
        for (const uint32_t v : tri) ++start[v + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    {
        std::vector<uint32_t> fill(start.begin(), start.end() - 1);
        for (uint32_t t = 0; t < triangleCount; ++t)
            for (uint32_t c = 0; c < 3; ++c) corners[fill[mesh.triangles[t][c]]++] = t * 3 + c;
    }

    // Step 3: per vertex, join triangles across smooth edges; one output vertex per group.
    TriangleMesh out;
    out.triangles = mesh.triangles;
    out.triangleMaterial = mesh.triangleMaterial;
    out.positions.reserve(vertexCount);
    out.normals.reserve(vertexCount);
    std::vector<uint32_t> parent, groupVertex;
    std::vector<Vec3> groupSum;
    for (uint32_t v = 0; v < vertexCount; ++v) {
        const uint32_t first = start[v], count = start[v + 1] - start[v];
        parent.resize(count);
        std::iota(parent.begin(), parent.end(), 0u);
        auto root = [&](uint32_t i) {
            while (parent[i] != i) i = parent[i] = parent[parent[i]];
            return i;
        };
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t ti = corners[first + i] / 3, ci = corners[first + i] % 3;
            const uint32_t nextI = mesh.triangles[ti][(ci + 1) % 3];
            const uint32_t prevI = mesh.triangles[ti][(ci + 2) % 3];
            for (uint32_t j = i + 1; j < count; ++j) {
                const uint32_t tj = corners[first + j] / 3, cj = corners[first + j] % 3;
                const uint32_t nextJ = mesh.triangles[tj][(cj + 1) % 3];
                const uint32_t prevJ = mesh.triangles[tj][(cj + 2) % 3];
                const bool shareEdge =
                    nextI == prevJ || prevI == nextJ || nextI == nextJ || prevI == prevJ;
                if (shareEdge && glm::dot(faceNormal[ti], faceNormal[tj]) >= minCos)
                    parent[root(i)] = root(j);
            }
        }
        // Angle-weighted normal sums per group.
        groupVertex.assign(count, UINT32_MAX);
        groupSum.assign(count, Vec3(0.0));
        uint32_t groups = 0;
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t r = root(i);
            if (groupVertex[r] == UINT32_MAX) {
                groupVertex[r] = uint32_t(out.positions.size());
                out.positions.push_back(mesh.positions[v]);
                out.normals.emplace_back(0.0);
                ++groups;
            }
            const uint32_t t = corners[first + i] / 3, c = corners[first + i] % 3;
            const Vec3 e1 = corner(t, (c + 1) % 3) - corner(t, c);
            const Vec3 e2 = corner(t, (c + 2) % 3) - corner(t, c);
            const double l1 = glm::length(e1), l2 = glm::length(e2);
            const double angle =
                l1 > 0.0 && l2 > 0.0
                    ? std::acos(std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0, 1.0))
                    : 0.0;
            groupSum[r] += angle * faceNormal[t];
            out.triangles[t][c] = groupVertex[r];
        }
        const bool hasInput = !mesh.normals.empty() && glm::length(mesh.normals[v]) > 0.0;
        const bool exact = groups == 1 && hasInput;
        for (uint32_t i = 0; i < count; ++i) {
            if (groupVertex[i] == UINT32_MAX) continue;
            const double len = glm::length(groupSum[i]);
            Vec3& n = out.normals[groupVertex[i]];
            if (exact || (!(len > 0.0) && hasInput))
                n = glm::normalize(mesh.normals[v]);
            else if (len > 0.0)
                n = groupSum[i] / len;
            else
                n = Vec3(0.0, 0.0, 1.0);
        }
    }
    return out;
}

}  // namespace csg
