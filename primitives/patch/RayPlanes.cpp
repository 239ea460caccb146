#include "primitives/patch/RayPlanes.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

// At most this many Newton steps: from a start inside the basin ~6 suffice (quadratic
// convergence from 1e-2); the rest covers linear convergence at a tangency.
constexpr int kMaxNewtonSteps = 40;

}  // namespace

RayPlanes::RayPlanes(const Vec3& origin, const Vec3& direction) : o(origin), d(direction) {
    // n1: perpendicular to d, built from d's smallest component's axis (never parallel to d).
    const Vec3 a = glm::abs(d);
    const Vec3 axis = a.x <= a.y && a.x <= a.z ? Vec3(1, 0, 0)
                      : a.y <= a.z             ? Vec3(0, 1, 0)
                                               : Vec3(0, 0, 1);
    const Vec3 dn = d / glm::length(d);
    n1 = glm::normalize(glm::cross(dn, axis));
    n2 = glm::cross(dn, n1);
}

bool newtonOnRay(const BezierPatch& patch, const RayPlanes& planes, double& u, double& v) {
    const double scale = patchSize(patch);
    for (int step = 0; step < kMaxNewtonSteps; ++step) {
        // Step 1: residual and Jacobian at (u, v).
        const Vec2 f = planes.distances(patch.eval(u, v));
        const Vec3 su = patch.du(u, v), sv = patch.dv(u, v);
        const double a = glm::dot(planes.n1, su), b = glm::dot(planes.n1, sv);
        const double c = glm::dot(planes.n2, su), e = glm::dot(planes.n2, sv);
        const double det = a * e - b * c;
        // Step 2: a singular Jacobian: converged only if the residual is rounding noise.
        if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
            const bool atRoot = std::abs(f.x) + std::abs(f.y) <=
                                tol::kPatchSingularResidualUlps * tol::kUlp * scale;
            return atRoot && u >= -tol::kPatchParamSlack && u <= 1 + tol::kPatchParamSlack &&
                   v >= -tol::kPatchParamSlack && v <= 1 + tol::kPatchParamSlack;
        }
        const double du = (e * f.x - b * f.y) / det, dv = (a * f.y - c * f.x) / det;
        if (!std::isfinite(du) || !std::isfinite(dv)) return false;
        u -= du;
        v -= dv;
        // Step 3: far outside the square: not this patch's root (keeps S's evaluation sane).
        if (std::abs(u - 0.5) > 2.0 || std::abs(v - 0.5) > 2.0) return false;
        if (std::max(std::abs(du), std::abs(dv)) < tol::kPatchNewtonStep) {
            if (u < -tol::kPatchParamSlack || u > 1 + tol::kPatchParamSlack ||
                v < -tol::kPatchParamSlack || v > 1 + tol::kPatchParamSlack)
                return false;
            u = std::clamp(u, 0.0, 1.0);
            v = std::clamp(v, 0.0, 1.0);
            return true;
        }
    }
    return false;
}

double crossingGap(const BezierPatch& patch, const Vec3& d) {
    return tol::kPatchDedupeRel * patchSize(patch) / glm::length(d);
}

void sortCrossings(PatchCrossing* out, int n) {
    std::sort(out, out + n, [](const PatchCrossing& a, const PatchCrossing& b) {
        return a.t < b.t || (a.t == b.t && (a.u < b.u || (a.u == b.u && a.v < b.v)));
    });
}

double patchSize(const BezierPatch& patch) {
    const Bounds3 b = patch.hullBounds();
    return glm::length(b.extent());
}

}  // namespace csg
