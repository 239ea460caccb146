// A polygon mesh bounding a solid: polyhedron() and import() in the language.
//
// Notation: the mesh's line is o + t d in its local frame; a crossing is (t, triangle). The
// solid is the set of points from which a ray crosses the triangles an odd number of times
// (crossing parity): the winding of the faces plays no part, as for OpenSCAD 2021's closed
// meshes, so a mesh given clockwise, counter-clockwise or with some faces turned is the same
// solid.
//
// Crossings: the watertight test of Woop, Benthin and Wald (JCGT 2013): the ray becomes the
// z axis of a sheared frame, each vertex is projected there once per ray (the same bits in
// every triangle that shares it), and a triangle is crossed when the ray's point lies on the
// same side of its three edges. The side of an edge (P, Q) is the sign of the 2x2 determinant
// Q.x P.y - Q.y P.x, computed EXACTLY (a filter, then error-free products where the filter
// cannot tell). Where it is exactly zero (the ray meets the edge or a vertex), the sign is
// that of the ray moved by (eps, eps^2) in the sheared frame, eps -> 0 (simulation of
// simplicity): Q.y - P.y, else P.x - Q.x. Why this keeps span pairing: every edge's side is
// decided once, by an antisymmetric rule, for one actual (perturbed) line that passes through
// no projected vertex and no projected edge, so the triangles crossed are exactly those whose
// projection holds that line's point. The projection of a closed mesh (every edge shared by an
// even number of triangles) covers a point that lies on no projected edge an even number of
// times, whatever the rounded vertex positions, so the crossings of every line pair up: a ray
// through a vertex or along an edge counts each surface crossing once, as a nudged ray does,
// and a ray grazing an edge or lying in a face's plane counts 0 or 2 there (a zero-length
// span, dropped by the caller). The BVH boxes are widened by tol::kMeshBoxMarginRel so that no
// triangle this test crosses is culled by its box.
//
// Polygon methods (--polygon-method; Polyhedron::method): the crossing test above is the
// default, Watertight. The ray-tracing lecture's two methods are there to compare with it:
//   Snyder   the line meets the triangle's plane at t = n . (P0 - o) / (n . d); the hit point's
//            barycentric coordinates b_i come from 2x2 cross products in the projection that
//            drops the normal's largest axis, and it is inside when every b_i is in [0, 1];
//   Marchal  the same plane point I; in the plane, the half-line from P0 through I crosses the
//            opposite edge P1 P2 at M (when P1 and P2 lie strictly on either side of it), and I
//            is inside when |P0 I| < |P0 M|.
// Both compute each triangle's normal per test (no per-triangle planes are stored) and decide
// every triangle alone, in rounded arithmetic: a line through a shared edge or vertex may be
// counted by both triangles or by neither, so a line's crossings may not pair (spans() then
// drops the last of an odd count). bench/mesh_bench measures how often, against Watertight's
// never. Their normal() interpolates corner normals: Snyder by b0 N0 + b1 N1 + b2 N2, Marchal by
// N_M = (1 - s) N1 + s N2 at M = P1 + s (P2 - P1), then (1 - r) N0 + r N_M with r = |P0 I| /
// |P0 M| (the same weights, reached another way). A corner's normal is the angle-weighted mean
// of the normals of the triangles around the vertex that turn less than kSmoothCreaseDegrees
// from this triangle's, so a faceted sphere shades round while a cube keeps its edges. The
// method changes spans() and normal() only: inside() and crossings(), which decide orientation
// and membership, stay watertight.
//
// Faces: a span end's face is the crossed triangle's index modulo kFaceIds (65535; kClipFace is
// the 65536th value), so meshes of up to 65535 triangles name the triangle itself; in larger
// ones normal() takes, among the triangles of that residue, the one nearest the point (the
// point lies on the crossed one up to rounding): n / 65535 candidates, paid only when a normal
// is asked for (shading, probe, export), never by a ray.
//
// Capacity: a line with more than LocalSpans::kCapacity (32) spans keeps its first entry and
// last exit and loses its narrowest gaps: the gaps between consecutive spans are closed,
// narrowest first (the first in t on a tie), until 32 spans remain. So nothing solid is ever
// dropped, the first and last surfaces along the line are exact, and the solid grows only by
// the thinnest voids along that one line. (The capacity stays 32: LocalSpans lives on the
// stack of the recursive CSG walk, one per level.)
//
// First span: closest() and any() on a mesh that is a whole object read only its first span
// past `from` (LocalSpans::firstOnly). A closed mesh under the watertight test, whose
// crossings pair up along every line, then gathers them nearer boxes first, only up to a
// horizon just past the first one past `from`, and a line that starts inside the mesh's box
// is searched ahead of `from` first (no crossing there: no span). The other hints are ignored,
// and open meshes and the other methods always answer with the whole list.
//
// Open meshes (some edge used by an odd number of triangles): the line's crossings are paired
// as above and, when their count is odd, the last one is dropped; the io layer warns at the
// call with the edge counts. Normals point out of the parity solid: each connected sheet of
// consistently wound triangles is turned, as a whole, so that a ray from its largest
// triangle's centroid along the normal leaves the solid (an even count of crossings ahead).
#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include "primitives/Primitive.h"
#include "primitives/base/Accel.h"
#include "primitives/base/Grid.h"
#include "primitives/base/WideBvh.h"

namespace csg {

struct PolyhedronData;
struct MeshStructure;

// How spans() tests a line against the triangles (see the head of this file).
enum class PolygonMethod : uint8_t { Watertight, Snyder, Marchal };
// The names of --polygon-method, in the enum's order.
inline constexpr std::array<std::string_view, 3> kPolygonMethodNames = {"watertight", "snyder",
                                                                        "marchal"};
inline const char* polygonMethodName(PolygonMethod method) {
    return kPolygonMethodNames[static_cast<size_t>(method)].data();
}
// The method of a name polygonMethodName gives; nullopt for anything else.
std::optional<PolygonMethod> parsePolygonMethod(std::string_view name);
// Triangles whose normals turn more than this from each other meet at a crease: their corner
// normals are not averaged (30 degrees: OpenSCAD's default facets, 12 degrees apart, shade
// round; a cube's 90-degree edges and a hexagonal prism's 60 stay sharp).
inline constexpr double kSmoothCreaseDegrees = 30.0;

// Faces as lists of corners: face f is corners[faceStart[f]] .. corners[faceStart[f + 1] - 1],
// indices into the points; faceStart has one entry more than there are faces.
struct PolygonFaces {
    std::vector<uint32_t> corners;
    std::vector<uint32_t> faceStart{0};

    size_t size() const { return faceStart.size() - 1; }
    void add(std::initializer_list<uint32_t> face) {
        corners.insert(corners.end(), face);
        faceStart.push_back(static_cast<uint32_t>(corners.size()));
    }
    void closeFace() { faceStart.push_back(static_cast<uint32_t>(corners.size())); }
};

// How the triangles meet along their edges (vertices welded by exact position).
struct MeshEdges {
    uint64_t edges = 0;        // distinct edges
    uint64_t openEdges = 0;    // used by an odd number of triangles (1: a boundary)
    uint64_t manyFaces = 0;    // used by more than two triangles
    uint64_t misoriented = 0;  // used by two triangles that run it the same way
    bool closed() const { return openEdges == 0; }
    bool manifold() const { return openEdges == 0 && manyFaces == 0; }
};

struct Polyhedron {
    static constexpr const char* kName = "polyhedron";
    // Face ids in a span end: the triangle index modulo this (see the head of this file).
    static constexpr uint32_t kFaceIds = 65535;
    static uint16_t faceOf(uint32_t triangle) { return uint16_t(triangle % kFaceIds); }
    // Most triangles a mesh may have: the BVH's depth bound (primitives/base/WideBvh.h).
    static constexpr uint64_t kMaxTriangles = uint64_t(1) << 24;
    // invalidReason() of a mesh with no face of positive area (the empty solid to a caller).
    static constexpr const char* kNoFaces = "the mesh has no faces of positive area";

    std::shared_ptr<const PolyhedronData> data;        // shared, immutable
    PolygonMethod method = PolygonMethod::Watertight;  // set by Scene::compile's options
    // What spans() walks to find the triangles a line may cross (--accel, set by
    // Scene::compile): null for the mesh's own SAH BVH (data->nodes), else another of the
    // lecture's structures over the same triangles. Every structure yields the same crossings.
    std::shared_ptr<const MeshStructure> structure;

    // The faces of this mesh organized by `accel` (primitives/base/Accel.h), to be shared by
    // every leaf placing it; null for the SAH and for auto, which keeps the SAH on a mesh's
    // faces (Polyhedron.cpp says why). A mesh that is not valid gets none.
    static std::shared_ptr<const MeshStructure> organize(const PolyhedronData& data, Accel accel);

    // Builds the mesh from points (finite) and faces of at least 3 corners (indices below
    // points.size(); checked by the caller). Corners at equal positions are welded; faces of
    // more than 3 corners are triangulated in their projection along their Newell normal,
    // dropping its largest axis: a fan from the first corner when the polygon is convex there,
    // else ear clipping (a non-planar face's surface is that triangulation's); faces of no
    // area (fewer than 3 distinct corners) are dropped. Never throws; bad input shows in
    // invalidReason().
    static Polyhedron make(std::vector<Vec3> points, const PolygonFaces& faces);

    const char* invalidReason() const;
    Bounds3 bounds() const;
    // The spans of the line by crossing parity (see the head of this file); at most
    // LocalSpans::kCapacity, gaps closed beyond that.
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    // Parity of the crossings ahead of p along a fixed direction.
    bool inside(const Vec3& p) const;
    // The plane normal of triangle `face` (flat shading), pointing out of the solid; +z for a
    // triangle of no area.
    Vec3 normal(const Vec3& p, uint16_t face) const;
    // Triangles, vertices, whether closed.
    void describe(JsonWriter& json) const;

    // One crossing, for tests and spans().
    struct Crossing {
        double t;
        uint32_t triangle;
    };
    // Every crossing of the line o + t d, ascending in t (then triangle), into `out` (cleared).
    void crossings(const Vec3& o, const Vec3& d, std::vector<Crossing>& out) const;
    // Edge statistics of the welded triangles.
    const MeshEdges& edges() const;
    size_t triangleCount() const;
};

struct PolyhedronData {
    std::vector<Vec3> vertices;                      // welded, numbered in BVH order of first use
    std::vector<std::array<uint32_t, 3>> triangles;  // BVH leaf order, wound outward
    std::vector<BvhNode> nodes;                      // over widened triangle boxes
    uint32_t root = 0;
    Bounds3 box;
    MeshEdges edges;
    uint64_t droppedFaces = 0;  // faces of no area
    const char* invalid = nullptr;
    // Each triangle's corner normals for the interpolating methods, built on first use.
    mutable std::once_flag smoothOnce;
    mutable std::vector<std::array<Vec3, 3>> cornerNormals;
};

// The triangles of a mesh (in PolyhedronData's order, so face ids and the order of crossings at
// one t stay those of the SAH) organized by another of --accel's structures: a median-cut or
// Goldsmith-Salmon BVH, whose leaves list triangles through leafTriangles, or a uniform or
// non-uniform grid listing triangle indices, each triangle tested once per line (a per-thread
// mailbox) however many cells list it.
struct MeshStructure {
    Accel accel = Accel::Median;
    std::vector<BvhNode> nodes;  // the BVH (median cut, Goldsmith-Salmon)
    uint32_t root = 0;
    std::vector<uint32_t> leafTriangles;  // a BVH leaf's position -> triangle index
    UniformGrid grid;                     // Accel::Grid
    HalvingGrid halving;                  // Accel::NonUniformGrid

    size_t bytes() const;
};

}  // namespace csg
