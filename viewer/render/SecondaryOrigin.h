// Where a secondary ray (shadow, reflection, refraction) starts: the hit point moved off the
// surface by a bound on its own rounding error, pbrt's way, so the new ray can neither re-hit
// the surface it leaves (acne, speckles) nor tunnel through a thin wall, at any scale: the
// offset grows with |o| + |t d|, not with a fixed epsilon.
#pragma once

#include "csg/Ray.h"
#include "primitives/base/Math.h"
#include "primitives/base/Tolerances.h"

namespace viewer::render {

// Per-component bound on |computed - true| of the hit point ray.at(t).
inline csg::Vec3 hitPointError(const csg::Ray& ray, double t) {
    constexpr double kRel = csg::tol::gamma(csg::tol::kHitPointErrorOps);
    return kRel * (glm::abs(ray.o) + glm::abs(t * ray.d));
}

// point moved along the unit normal n, to the side that direction leaves toward, by the
// projection of the error box onto n (the farthest the true surface can be along n). The
// new ray o + t direction with t in (0, ...] then starts strictly on that side.
inline csg::Vec3 offsetRayOrigin(const csg::Vec3& point, const csg::Vec3& error, const csg::Vec3& n,
                                 const csg::Vec3& direction) {
    const double distance = glm::dot(glm::abs(n), error);
    const csg::Vec3 offset = distance * n;
    return glm::dot(direction, n) < 0.0 ? point - offset : point + offset;
}

}  // namespace viewer::render
