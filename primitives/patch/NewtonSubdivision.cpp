// Notation: a piece is the patch restricted to [u0, u1] x [v0, v1] with its own 16 control
// points (de Casteljau halves), kept on a fixed stack walked depth first.
#include "primitives/patch/NewtonSubdivision.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/Tolerances.h"
#include "primitives/patch/RayPlanes.h"

namespace csg {

namespace {

// Halvings along one path: 2^-24 of the patch is far below any flatness need (a piece that
// small is flat within 1e-3 unless the patch is degenerate there, e.g. at a pole, where Newton
// from its centre still converges); it bounds the stack (one entry per level, plus one).
constexpr int kMaxDepth = 48;

struct Piece {
    BezierPatch net;
    double u0, u1, v0, v1;
    int depth;
};

// Splits the cubic p[0], p[s], p[2s], p[3s] at 1/2 into left (written over p) and right.
void halveCurve(Vec3* p, Vec3* right, int s) {
    const Vec3 p01 = 0.5 * (p[0] + p[s]), p12 = 0.5 * (p[s] + p[2 * s]),
               p23 = 0.5 * (p[2 * s] + p[3 * s]);
    const Vec3 p012 = 0.5 * (p01 + p12), p123 = 0.5 * (p12 + p23);
    const Vec3 mid = 0.5 * (p012 + p123);
    right[0] = mid, right[s] = p123, right[2 * s] = p23, right[3 * s] = p[3 * s];
    p[s] = p01, p[2 * s] = p012, p[3 * s] = mid;
}

// Halves a piece along u or v: a keeps the lower half, b gets the upper one.
void halve(Piece& a, Piece& b, bool alongU) {
    b = a;
    for (int k = 0; k < 4; ++k) {
        if (alongU)
            halveCurve(a.net.points.data() + k, b.net.points.data() + k, 4);
        else
            halveCurve(a.net.points.data() + 4 * k, b.net.points.data() + 4 * k, 1);
    }
    double& hiA = alongU ? a.u1 : a.v1;
    double& loB = alongU ? b.u0 : b.v0;
    hiA = loB = 0.5 * ((alongU ? a.u0 : a.v0) + hiA);
    a.depth = b.depth = a.depth + 1;
}

// Are the piece's control points within kPatchFlatRel of its size from the plane of its
// corner diagonals?
bool flat(const BezierPatch& net, const Bounds3& box) {
    const Vec3 n = glm::cross(net.at(3, 3) - net.at(0, 0), net.at(3, 0) - net.at(0, 3));
    const double len = glm::length(n);
    if (!(len > 0.0)) return false;
    const Vec3 c = 0.25 * (net.at(0, 0) + net.at(0, 3) + net.at(3, 0) + net.at(3, 3));
    const double bound = tol::kPatchFlatRel * glm::length(box.extent()) * len;
    for (const Vec3& p : net.points)
        if (std::abs(glm::dot(n, p - c)) > bound) return false;
    return true;
}

}  // namespace

int intersectByNewton(const BezierPatch& patch, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    const RayPlanes planes(o, d);
    const SlabRay slab(o, d);
    Piece stack[kMaxDepth + 2];
    int pending = 0;
    stack[pending++] = {patch, 0.0, 1.0, 0.0, 1.0, 0};
    int n = 0;
    const double gap = crossingGap(patch, d);
    while (pending > 0) {
        Piece p = stack[--pending];
        // Step 1: the piece's control box must meet the line.
        const Bounds3 box = p.net.hullBounds();
        double t0 = -kInfinity, t1 = kInfinity;
        if (!clipToBox(slab, box, t0, t1)) continue;
        // Step 2: not flat yet: halve across the longer direction (in space).
        if (p.depth < kMaxDepth && !flat(p.net, box)) {
            const double lu = glm::length(p.net.at(3, 0) - p.net.at(0, 0)) +
                              glm::length(p.net.at(3, 3) - p.net.at(0, 3));
            const double lv = glm::length(p.net.at(0, 3) - p.net.at(0, 0)) +
                              glm::length(p.net.at(3, 3) - p.net.at(3, 0));
            Piece& a = stack[pending++];
            a = p;
            halve(a, stack[pending++], lu >= lv);
            continue;
        }
        // Step 3: Newton from the centre; keep a root that lies in this piece.
        double u = 0.5 * (p.u0 + p.u1), v = 0.5 * (p.v0 + p.v1);
        if (!newtonOnRay(patch, planes, u, v)) continue;
        const double mu = tol::kPatchOwnMargin * (p.u1 - p.u0) + tol::kPatchParamSlack,
                     mv = tol::kPatchOwnMargin * (p.v1 - p.v0) + tol::kPatchParamSlack;
        if (u < p.u0 - mu || u > p.u1 + mu || v < p.v0 - mv || v > p.v1 + mv) continue;
        addCrossing(out, n, {planes.rayParameter(patch.eval(u, v)), u, v}, gap);
    }
    sortCrossings(out.data(), n);
    return n;
}

}  // namespace csg
