// A convex polyhedron as the intersection of closed half-spaces n_i . p <= c_i: OpenSCAD's
// faceted cylinders and spheres (io/Faceting.h builds their vertices and faces, vertex for
// vertex as OpenSCAD does), and later any convex hull. The lecture's polyhedral bounding-volume
// test, used as a primitive: a line is inside every half-space from the latest entry to the
// earliest exit.
// Faces: the plane index (0 ..), so at most kMaxPlanes planes (kClipFace is reserved).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "primitives/Primitive.h"

namespace csg {

struct ConvexPolytopeData;

// Where a polytope came from, for describe(): "cylinder" with its fragment count, "sphere" with
// its fragments and rings. Null module: not described.
struct PolytopeOrigin {
    const char* module = nullptr;
    uint32_t fragments = 0;
    uint32_t rings = 0;  // 0 when the solid has no rings (a cylinder)
};

struct ConvexPolytope {
    // What info and probe call it: the language has no module of this name, but every OpenSCAD
    // user knows a polyhedron, and describe() names the module it was faceted from.
    static constexpr const char* kName = "convex_polyhedron";
    static constexpr bool kConvex = true;
    // Face ids are uint16_t and kClipFace (0xffff) marks a span end that is not a surface.
    static constexpr uint32_t kMaxPlanes = kClipFace;

    using Origin = PolytopeOrigin;

    std::shared_ptr<const ConvexPolytopeData> data;  // shared, immutable

    // Builds the polytope of a closed convex polyhedron: face f has the vertices
    // faceVertices[faceStarts[f] .. faceStarts[f + 1]) (faceStarts has one entry more than
    // there are faces), in either winding. Each face becomes one plane through its vertices,
    // turned away from the centroid of all vertices and pushed out to the face vertex farthest
    // along it, so every given vertex satisfies every plane as inside() computes it. Never
    // throws on bad input: invalidReason() says what is wrong (more than kMaxPlanes faces,
    // non-finite vertices, a face without area). Callers bound the face count before building
    // the vertices: see io/Faceting.h.
    static ConvexPolytope fromFaces(std::vector<Vec3> vertices,
                                    std::span<const uint32_t> faceVertices,
                                    std::span<const uint32_t> faceStarts, Origin origin = {});

    const char* invalidReason() const;
    // The box of the vertices.
    Bounds3 bounds() const;
    // Exact: the box of the transformed vertices.
    Bounds3 boundsUnder(const Mat4& m) const;
    // At most one span: from the latest entry through a plane facing the line's origin to the
    // earliest exit through a plane facing away, each end's face that plane (the first such
    // plane on a tie, as at an edge or a vertex). A line parallel to a plane and outside it
    // misses; one inside every plane it is parallel to is bounded by the others.
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const;
    // The unit outward normal of plane `face`.
    Vec3 normal(const Vec3& p, uint16_t face) const;
    // Its origin ("faceted", "fragments", "rings"), plane and vertex counts.
    void describe(JsonWriter& json) const;
    // A ball about the local origin or the box's centre, whichever is smaller, through the
    // farthest vertex, when its volume is below the box's (a faceted sphere: its circumscribed
    // sphere); otherwise radius = infinity, which compile takes as no ball (a ball looser than
    // the box only costs a test per ray).
    LocalBall boundingBall() const;

    size_t planeCount() const;
};

// One plane of a polytope: the closed half-space dot(normal, p) <= offset, normal unit length.
struct PolytopePlane {
    Vec3 normal;
    double offset = 0.0;
};

// Four planes side by side, for the ray loop (ConvexPolytope::spans). A GCC/Clang vector
// extension: AVX where the build may use it, two SSE2 halves otherwise; each lane does the
// operations of the scalar form in the same order, so its bits are the same.
inline constexpr size_t kPlaneLanes = 4;
using PlaneLanes = double __attribute__((vector_size(kPlaneLanes * sizeof(double))));
using PlaneMask = int64_t __attribute__((vector_size(kPlaneLanes * sizeof(int64_t))));
struct PlaneBlock {
    PlaneLanes nx, ny, nz, offset;
};

struct ConvexPolytopeData {
    std::vector<PolytopePlane> planes;    // in face order: face id = index
    std::vector<PlaneBlock> planeBlocks;  // the same planes, planes[4 b + k] in block b lane k
    std::vector<Vec3> vertices;
    // The faces as given to fromFaces (vertex indices; face f is faceVertices[faceStarts[f] ..
    // faceStarts[f + 1])): the boundary, for clients that need it as polygons (projection).
    std::vector<uint32_t> faceVertices, faceStarts;
    Bounds3 box;
    LocalBall ball{Vec3(0.0), kInfinity};
    ConvexPolytope::Origin origin;
    const char* invalid = nullptr;
};

}  // namespace csg
