#include "csg/section/LeafMesh.h"

#include <span>
#include <stdexcept>

#include "csg/Scene.h"
#include "csg/mesh/Tessellate.h"

namespace csg {

namespace {

void addVertex(WorldMesh& out, const Mat4& m, const Vec3& p) {
    const Vec3 v = transformPoint(m, p);
    out.vertices.push_back(v);
    out.box.extend(v);
}

// A polygon of corner indices as a fan from its first corner: exact for the convex faces of a
// box or a convex polytope.
void addFan(WorldMesh& out, uint32_t offset, std::span<const uint32_t> face) {
    for (size_t k = 1; k + 1 < face.size(); ++k)
        out.triangles.push_back({offset + face[0], offset + face[k], offset + face[k + 1]});
}

void addBox(WorldMesh& out, const Box& box, const Mat4& m) {
    // Corner i has x from bit 0, y from bit 1, z from bit 2 (0: lo, 1: hi).
    for (uint32_t i = 0; i < 8; ++i)
        addVertex(out, m,
                  Vec3(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                       i & 4 ? box.hi.z : box.lo.z));
    static constexpr uint32_t kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                              {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const auto& face : kFaces) addFan(out, 0, face);
}

void addPolytope(WorldMesh& out, const ConvexPolytope& polytope, const Mat4& m) {
    const ConvexPolytopeData& data = *polytope.data;
    for (const Vec3& v : data.vertices) addVertex(out, m, v);
    for (size_t f = 0; f + 1 < data.faceStarts.size(); ++f)
        addFan(out, 0,
               std::span<const uint32_t>(data.faceVertices)
                   .subspan(data.faceStarts[f], data.faceStarts[f + 1] - data.faceStarts[f]));
}

void addPolyhedron(WorldMesh& out, const Polyhedron& mesh, const Mat4& m) {
    const PolyhedronData& data = *mesh.data;
    for (const Vec3& v : data.vertices) addVertex(out, m, v);
    out.triangles = data.triangles;
}

}  // namespace

bool isPolyhedral(const Primitive& shape) {
    return std::holds_alternative<Box>(shape) || std::holds_alternative<ConvexPolytope>(shape) ||
           std::holds_alternative<Polyhedron>(shape);
}

WorldMesh leafMesh(const Primitive& shape, const Mat4& worldFromLocal, double tolerance) {
    WorldMesh out;
    if (const auto* box = std::get_if<Box>(&shape)) {
        addBox(out, *box, worldFromLocal);
        return out;
    }
    if (const auto* polytope = std::get_if<ConvexPolytope>(&shape)) {
        addPolytope(out, *polytope, worldFromLocal);
        return out;
    }
    if (const auto* mesh = std::get_if<Polyhedron>(&shape)) {
        addPolyhedron(out, *mesh, worldFromLocal);
        return out;
    }
    if (const auto* e = std::get_if<Extrusion>(&shape); e && e->kind == Extrusion::Kind::Plane)
        throw std::invalid_argument("a 2-D shape has no bounded solid to project");
    // Mesh the leaf alone, in the frame asked for.
    const Scene scene = Scene::compile(transformed(worldFromLocal, leaf(shape)));
    TessellateOptions options;
    options.tolerance = tolerance;
    options.simplify = false;  // see kLeafMeshToleranceRel in Projection.h
    TessellateResult meshed = tessellate(scene, options);
    out.exact = false;
    out.error = std::max(meshed.error.max, meshed.backError.max);
    out.vertices = std::move(meshed.mesh.positions);
    out.triangles = std::move(meshed.mesh.triangles);
    for (const Vec3& v : out.vertices) out.box.extend(v);
    return out;
}

}  // namespace csg
