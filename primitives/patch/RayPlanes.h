// The ray as the meet of two planes, and what every patch method does with a candidate (u, v):
// polish it by 2-D Newton, read t, and list the crossings sorted and once each.
// Notation: the line is o + t d; n1, n2 are unit normals of two orthogonal planes through it;
// the patch meets the line where f_k(u, v) = n_k . (S(u, v) - o) are both zero.
#pragma once

#include <cmath>

#include "primitives/patch/BezierPatch.h"

namespace csg {

struct RayPlanes {
    Vec3 o, d;
    Vec3 n1, n2;  // unit, orthogonal to d and to each other

    RayPlanes(const Vec3& origin, const Vec3& direction);

    // The two plane distances of a point.
    Vec2 distances(const Vec3& p) const { return {glm::dot(n1, p - o), glm::dot(n2, p - o)}; }
    // The ray parameter of the point of the line nearest p.
    double rayParameter(const Vec3& p) const { return glm::dot(d, p - o) / glm::dot(d, d); }
};

// 2-D Newton on (f1, f2) from (u, v). True when it converged (a step below
// tol::kPatchNewtonStep) to a point within tol::kPatchParamSlack of [0, 1]^2; u and v are then
// the root clamped onto the square. A singular Jacobian (the ray tangent to the patch, or a
// pole) ends the iteration as not converged unless the residual is already at rounding level.
bool newtonOnRay(const BezierPatch& patch, const RayPlanes& planes, double& u, double& v);

// Appends c to out[0, n) unless a crossing within `gap` in t is there already (a root found
// again from a neighbouring region) or out is full: the one dedupe of a patch's crossings, so
// any two listed are more than gap apart. gap: crossingGap().
inline void addCrossing(PatchCrossings& out, int& n, const PatchCrossing& c, double gap) {
    for (int k = 0; k < n; ++k)
        if (std::abs(out[k].t - c.t) <= gap) return;
    if (n < kMaxPatchCrossings) out[n++] = c;
}

// The t gap within which two crossings of the line o + t d with the patch are one:
// tol::kPatchDedupeRel * patchSize(patch) apart along the line.
double crossingGap(const BezierPatch& patch, const Vec3& d);

// Sorts out[0, n) by t (ties by u, then v, so the order never depends on the search's).
void sortCrossings(PatchCrossing* out, int n);

// Diagonal of the patch's control-point box: the size the dedupe rule is relative to.
double patchSize(const BezierPatch& patch);

}  // namespace csg
