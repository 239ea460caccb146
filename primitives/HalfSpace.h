// The closed half-space of points p with dot(planeNormal, p) <= offset: a plane and the side below
// it. Unbounded, so it is never put in a BVH; planeNormal need not be unit length.
#pragma once

#include "primitives/Primitive.h"

namespace csg {

struct HalfSpace {
    static constexpr const char* kName = "halfspace";
    static constexpr bool kConvex = true;
    static constexpr bool kPlanar = true;

    Vec3 planeNormal{0.0, 0.0, 1.0};
    double offset = 0.0;

    const char* invalidReason() const {
        const bool finite = std::isfinite(planeNormal.x) && std::isfinite(planeNormal.y) &&
                            std::isfinite(planeNormal.z) && std::isfinite(offset);
        return finite && planeNormal != Vec3(0.0) ? nullptr
                                                  : "halfspace needs a finite, non-zero normal";
    }

    // Face 0 is the plane. Bounds are everything unless the normal is axis-aligned, in which
    // case the bounded side is kept (z <= 2 gives lo = -inf, hi = (inf, inf, 2)).
    Bounds3 bounds() const;
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const { return glm::dot(planeNormal, p) <= offset; }
    Vec3 normal(const Vec3& p, uint16_t face) const;
    void describe(JsonWriter& json) const {
        json.key("normal").vec(planeNormal, 3).key("offset").value(offset);
    }
};

}  // namespace csg
