// Notation: the patch is seen in the plane of the ray's two normals (RayPlanes): each control
// point P_ij becomes q_ij = (n1 . (P_ij - o), n2 . (P_ij - o)), and the ray is the origin of
// that plane. A region is a sub-rectangle [u0, u1] x [v0, v1] of the parameter square with
// the 2-D control points of the patch restricted to it. Clipping in u measures the q_ij's
// distance to a line through the origin along the region's v-direction: those distances are
// the Bezier coefficients of a function of (u, v) that vanishes at every crossing, so the u
// where the convex hull of the points (i/3, distance_ij) meets zero bound the crossings' u.
#include "primitives/patch/Clip.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/Tolerances.h"
#include "primitives/patch/RayPlanes.h"

namespace csg {

namespace {

// A clip that keeps more than this fraction of a region in both directions is not converging
// (two crossings in the region, or a tangency): the region is split in half instead
// (Nishita et al.'s rule; Sederberg and Nishita use 20% reduction).
constexpr double kSplitWhenKept = 0.8;
// Regions live on a stack of this depth: each split pushes two and a depth-first walk pops
// one, so the depth is at most the number of halvings to kPatchClipWidth (~20 per direction).
constexpr int kStackDepth = 64;
// At most this many region steps per ray and patch: a ray lying in the patch has a curve of
// crossings that clipping can never exclude; this bounds the work spent on it.
constexpr int kMaxSteps = 2048;

struct Region {
    Vec2 q[16];  // q[4 i + j], i along u
    double u0, u1, v0, v1;
};

// The cubic Bezier coefficients c[0..3] (stride apart in q) restricted to [a, b] of [0, 1].
void restrictCurve(Vec2* c, int stride, double a, double b) {
    Vec2 p[4] = {c[0], c[stride], c[2 * stride], c[3 * stride]};
    // Keep [0, b]: the left half of de Casteljau at b.
    if (b < 1.0) {
        const Vec2 p01 = glm::mix(p[0], p[1], b), p12 = glm::mix(p[1], p[2], b),
                   p23 = glm::mix(p[2], p[3], b);
        const Vec2 p012 = glm::mix(p01, p12, b), p123 = glm::mix(p12, p23, b);
        p[1] = p01, p[2] = p012, p[3] = glm::mix(p012, p123, b);
    }
    // Keep [a / b, 1] of that: the right half at a / b.
    const double s = b > 0.0 ? a / b : 0.0;
    if (s > 0.0) {
        const Vec2 p01 = glm::mix(p[0], p[1], s), p12 = glm::mix(p[1], p[2], s),
                   p23 = glm::mix(p[2], p[3], s);
        const Vec2 p012 = glm::mix(p01, p12, s), p123 = glm::mix(p12, p23, s);
        p[0] = glm::mix(p012, p123, s), p[1] = p123, p[2] = p23;
    }
    for (int k = 0; k < 4; ++k) c[k * stride] = p[k];
}

// Restricts the region's net to [a, b] (local) along u (alongU) or v.
void restrictRegion(Region& r, bool alongU, double a, double b) {
    if (a <= 0.0 && b >= 1.0) return;
    for (int k = 0; k < 4; ++k) {
        if (alongU)
            restrictCurve(r.q + k, 4, a, b);  // column j = k: i runs with stride 4
        else
            restrictCurve(r.q + 4 * k, 1, a, b);
    }
    double& lo = alongU ? r.u0 : r.v0;
    double& hi = alongU ? r.u1 : r.v1;
    const double w = hi - lo;
    hi = lo + b * w;
    lo = lo + a * w;
}

// The local range [lo, hi] of u (alongU) or v where the convex hull of the distance control
// points meets zero, widened by kPatchClipMargin; false when the hull misses zero.
bool clipRange(const Region& r, bool alongU, double& lo, double& hi) {
    // Step 1: the line through the origin along the other parameter's direction.
    auto at = [&](int i, int j) { return alongU ? r.q[4 * i + j] : r.q[4 * j + i]; };
    const Vec2 along = (at(0, 3) - at(0, 0)) + (at(3, 3) - at(3, 0));
    Vec2 normal(-along.y, along.x);
    if (!(glm::dot(normal, normal) > 0.0)) {
        normal = (at(3, 0) - at(0, 0)) + (at(3, 3) - at(0, 3));  // distance along our own
        if (!(glm::dot(normal, normal) > 0.0)) normal = Vec2(1.0, 0.0);
    }
    // Step 2: per control column i, the extreme distances (the hull of a column's points is
    // the segment between them).
    double mn[4], mx[4];
    for (int i = 0; i < 4; ++i) {
        mn[i] = kInfinity, mx[i] = -kInfinity;
        for (int j = 0; j < 4; ++j) {
            const double dist = glm::dot(normal, at(i, j));
            mn[i] = std::min(mn[i], dist), mx[i] = std::max(mx[i], dist);
        }
    }
    // Step 3: the hull meets zero on the hull of the columns containing zero and of the zero
    // crossings of segments between points of opposite sign.
    lo = kInfinity, hi = -kInfinity;
    for (int i = 0; i < 4; ++i)
        if (mn[i] <= 0.0 && mx[i] >= 0.0) lo = std::min(lo, i / 3.0), hi = std::max(hi, i / 3.0);
    for (int i = 0; i < 4; ++i)
        for (int k = i + 1; k < 4; ++k)
            for (double p : {mn[i], mx[i]})
                for (double q : {mn[k], mx[k]}) {
                    if (!((p < 0.0 && q > 0.0) || (p > 0.0 && q < 0.0))) continue;
                    const double x = (i + (k - i) * (p / (p - q))) / 3.0;
                    lo = std::min(lo, x), hi = std::max(hi, x);
                }
    if (!(lo <= hi)) return false;
    lo = std::max(0.0, lo - tol::kPatchClipMargin);
    hi = std::min(1.0, hi + tol::kPatchClipMargin);
    return true;
}

}  // namespace

int intersectByClip(const BezierPatch& patch, const Vec3& o, const Vec3& d, PatchCrossings& out) {
    const RayPlanes planes(o, d);
    Region stack[kStackDepth];
    int pending = 0;
    {
        Region& r = stack[pending++];
        for (int k = 0; k < 16; ++k) r.q[k] = planes.distances(patch.points[k]);
        r.u0 = r.v0 = 0.0, r.u1 = r.v1 = 1.0;
    }
    int n = 0;
    const double gap = crossingGap(patch, d);
    for (int steps = 0; pending > 0 && steps < kMaxSteps; ++steps) {
        Region r = stack[--pending];
        // Step 1: a small region: Newton from its centre finds the crossing in it.
        if (r.u1 - r.u0 <= tol::kPatchClipWidth && r.v1 - r.v0 <= tol::kPatchClipWidth) {
            double u = 0.5 * (r.u0 + r.u1), v = 0.5 * (r.v0 + r.v1);
            if (newtonOnRay(patch, planes, u, v))
                addCrossing(out, n, {planes.rayParameter(patch.eval(u, v)), u, v}, gap);
            continue;
        }
        // Step 2: clip both directions against the hull of the current net.
        double a, b, c, e;
        if (!clipRange(r, true, a, b) || !clipRange(r, false, c, e)) continue;
        restrictRegion(r, true, a, b);
        restrictRegion(r, false, c, e);
        // Step 3: too little removed: split the longer side; else clip again.
        if (b - a > kSplitWhenKept && e - c > kSplitWhenKept) {
            if (pending + 2 > kStackDepth) continue;  // unreachable by kStackDepth's bound
            const bool alongU = r.u1 - r.u0 >= r.v1 - r.v0;
            for (double half : {0.5, 0.0}) {
                Region& h = stack[pending++];
                h = r;
                restrictRegion(h, alongU, half, half + 0.5);
            }
            continue;
        }
        stack[pending++] = r;
    }
    sortCrossings(out.data(), n);
    return n;
}

}  // namespace csg
