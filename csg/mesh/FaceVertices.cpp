// The face vertices of Contourer (Contourer.h): where the surface curve on the face between two
// cells of a ring bends over a crease, or the face is ambiguous, a vertex on that face, decided
// once per face curve and kept in two layers of slots.
#include <algorithm>
#include <array>

#include "csg/mesh/CellTopology.h"
#include "csg/mesh/Contourer.h"
#include "csg/mesh/Qef.h"
#include "primitives/base/Tolerances.h"

namespace csg::detail {

// The face vertex decided for segment of the face at faceMin perpendicular to g. The fans
// of a cell at layer k (node z index) only meet faces at layers k - 1 and k, and cells come
// in layer order, so two layers of slots suffice; a slot layer is reset when it is reused
// for a new layer (only its written slots).
uint32_t& Contourer::faceSlot(const Node3& faceMin, int g, int segment) {
    const int z = faceMin[2];
    FaceLayer& layer = faceLayers_[size_t(z & 1)];
    if (layer.z != z) {
        if (layer.slots.empty())
            layer.slots.assign(size_t(spec_.nodes[0]) * size_t(spec_.nodes[1]) * 6, kUnknown);
        for (const uint32_t i : layer.written) layer.slots[i] = kUnknown;
        layer.written.clear();
        layer.z = z;
    }
    const uint32_t i =
        uint32_t(((uint64_t(faceMin[0]) + uint64_t(spec_.nodes[0]) * uint64_t(faceMin[1])) * 3 +
                  uint64_t(g)) *
                     2 +
                 uint64_t(segment));
    if (layer.slots[i] == kUnknown) layer.written.push_back(i);
    return layer.slots[i];
}

// Whether crease point x of the curve on an ambiguous face from crossing p0 (edge (a0, n0))
// to p1 (edge (a1, n1)) lies strictly inside the triangle of p0, p1 and the inside corner
// the curve goes around (the node the two edges share), in the face's axes u, v. The face's
// other curve stays in the triangle of the opposite corner, so two bent curves on one face
// cannot cross (a crease past the chord could reach over the other curve: the crossings
// of issue 7's random CSG where two sheets' fans met on an ambiguous face).
bool Contourer::bendsTowardCorner(const Vec3& x, const Vec3& p0, const Vec3& p1, const Node3& n0,
                                  int a0, const Node3& n1, int a1, int u, int v) const {
    Node3 corner = n0;
    Node3 n0End = n0, n1End = n1;
    ++n0End[a0];
    ++n1End[a1];
    if (n0End == n1 || n0End == n1End) corner = n0End;
    const Vec3 c = spec_.node(corner[0], corner[1], corner[2]);
    const Vec2 q(x[u], x[v]);
    const Vec2 t[3] = {{c[u], c[v]}, {p0[u], p0[v]}, {p1[u], p1[v]}};
    auto side = [&](const Vec2& from, const Vec2& to, const Vec2& at) {
        const Vec2 e = to - from, d = at - from;
        return e.x * d.y - e.y * d.x;
    };
    const double turn = side(t[0], t[1], t[2]);
    for (int i = 0; i < 3; ++i)
        if (!(side(t[i], t[(i + 1) % 3], q) * turn > 0.0)) return false;
    return true;
}

// The vertex on the face between two cells of edge (a, n0)'s ring, or kNone for a straight
// face curve. g is the axis the two cells differ on; h the other ring axis, dh its offset.
uint32_t Contourer::faceVertex(int a, const Node3& n0, int g, int h, int dh) {
    // Step 1: the face, its corners' signs, and which of its edges is ours.
    Node3 faceMin = n0;
    faceMin[h] += dh;
    const int u = (g + 1) % 3, v = (g + 2) % 3;
    std::array<bool, 4> corner;
    for (int dv = 0; dv < 2; ++dv)
        for (int du = 0; du < 2; ++du) {
            Node3 p = faceMin;
            p[u] += du;
            p[v] += dv;
            corner[size_t(du + 2 * dv)] = inside(p);
        }
    const int edgeAxis = a == u ? 0 : 1;
    const int segment = faceSegment(corner, edgeAxis, -dh);
    uint32_t& known = faceSlot(faceMin, g, segment);
    if (known != kUnknown) return known;

    // Step 2: the partner edge of the same face curve.
    int partnerAxis = -1, partnerOffset = -1;
    for (int ax = 0; ax < 2; ++ax)
        for (int o = 0; o < 2; ++o) {
            if (ax == edgeAxis && o == -dh) continue;
            const int c0 = ax == 0 ? 2 * o : o, c1 = ax == 0 ? 1 + 2 * o : o + 2;
            if (corner[size_t(c0)] == corner[size_t(c1)]) continue;
            if (faceSegment(corner, ax, o) == segment) {
                partnerAxis = ax;
                partnerOffset = o;
            }
        }
    Node3 partnerNode = faceMin;
    partnerNode[partnerAxis == 0 ? v : u] += partnerOffset;
    const EdgeSample s0 = sample(a, n0, stats_.missingCrossings);
    const EdgeSample s1 = sample(partnerAxis == 0 ? u : v, partnerNode, stats_.missingCrossings);

    // Step 3: bend the curve where the tangent lines meet; an ambiguous face always gets a
    // vertex, so two curves on one face never join the same two sheet vertices twice.
    const bool ambiguous = faceIsAmbiguous(corner);
    const Vec3 lo3 = spec_.node(faceMin[0], faceMin[1], faceMin[2]);
    Node3 faceMax = faceMin;
    ++faceMax[u];
    ++faceMax[v];
    const Vec3 hi3 = spec_.node(faceMax[0], faceMax[1], faceMax[2]);
    const Vec2 lo(lo3[u], lo3[v]), hi(hi3[u], hi3[v]);
    Vec3 crease;
    uint32_t vertex = kNone;
    // A crease point (almost) on one of the crossings adds nothing but a sliver triangle
    // that can fold onto its neighbour (tol::kCreaseVertexSeparation): skip it.
    const double apart =
        separation(std::min(hi[0] - lo[0], hi[1] - lo[1]), tol::kCreaseVertexSeparation);
    if (s0.measured && s1.measured &&
        creaseOnFace(s0.point, s0.normal, s1.point, s1.normal, u, v, lo, hi, crease) &&
        glm::length(crease - s0.point) > apart && glm::length(crease - s1.point) > apart &&
        (!ambiguous || bendsTowardCorner(crease, s0.point, s1.point, n0, a, partnerNode,
                                         partnerAxis == 0 ? u : v, u, v))) {
        crease[g] = lo3[g];
        vertex = addVertex(crease, Vec3(0.0));
    } else if (ambiguous) {
        Vec3 mid = 0.5 * (s0.point + s1.point);
        mid[g] = lo3[g];
        vertex = addVertex(mid, Vec3(0.0));
    }
    if (vertex != kNone) ++stats_.faceVertices;
    known = vertex;
    return vertex;
}

}  // namespace csg::detail
