// A solid ball of radius r centred at the local origin (OpenSCAD sphere(r)).
#pragma once

#include "primitives/Primitive.h"

namespace csg {

struct Sphere {
    static constexpr const char* kName = "sphere";
    static constexpr bool kConvex = true;
    double radius = 1.0;

    const char* invalidReason() const {
        return std::isfinite(radius) && radius > 0.0 ? nullptr : "sphere radius must be > 0";
    }

    Bounds3 bounds() const { return {Vec3(-radius), Vec3(radius)}; }
    // Exact: the image of a ball under an affine map is an ellipsoid whose extent along world
    // axis i is r times the length of row i of the linear part.
    Bounds3 boundsUnder(const Mat4& m) const;
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const { return glm::dot(p, p) <= radius * radius; }
    Vec3 normal(const Vec3& p, uint16_t face) const;
    void describe(JsonWriter& json) const { json.key("r").value(radius); }
    LocalBall boundingBall() const { return {Vec3(0.0), radius}; }
};

}  // namespace csg
