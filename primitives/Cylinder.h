// A solid truncated cone around the local z axis from z = 0 (radius r1) to z = h (radius r2):
// OpenSCAD cylinder(h, r1, r2) with center=false. r1 == r2 is a cylinder; r1 or r2 = 0 a cone.
#pragma once

#include "primitives/Primitive.h"

namespace csg {

struct Cylinder {
    static constexpr const char* kName = "cylinder";
    static constexpr bool kConvex = true;

    double height = 1.0;
    double r1 = 1.0;  // radius at z = 0, >= 0
    double r2 = 1.0;  // radius at z = height, >= 0 (not both 0)

    const char* invalidReason() const {
        const bool finite = std::isfinite(height) && std::isfinite(r1) && std::isfinite(r2);
        return finite && height > 0.0 && r1 >= 0.0 && r2 >= 0.0 && (r1 > 0.0 || r2 > 0.0)
                   ? nullptr
                   : "cylinder needs height > 0, radii >= 0 and not both radii 0";
    }

    // Faces: 0 = the lateral surface, 1 = the bottom cap (z = 0), 2 = the top cap (z = h).
    Bounds3 bounds() const;
    // Tight: the hull of the images of the two end discs.
    Bounds3 boundsUnder(const Mat4& m) const;
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const;
    // At the apex of a cone the lateral normal is undefined; the axis direction pointing away
    // from the base is returned there.
    Vec3 normal(const Vec3& p, uint16_t face) const;
    void describe(JsonWriter& json) const {
        json.key("h").value(height).key("r1").value(r1).key("r2").value(r2);
    }
};

}  // namespace csg
