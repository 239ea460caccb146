// A solid axis-aligned box [lo, hi] in its local frame (OpenSCAD cube(size, center)).
#pragma once

#include "primitives/Primitive.h"

namespace csg {

struct Box {
    static constexpr const char* kName = "cube";
    static constexpr bool kConvex = true;

    Vec3 lo{0.0};
    Vec3 hi{1.0};

    const char* invalidReason() const {
        const Bounds3 b{lo, hi};
        return b.finite() && lo.x < hi.x && lo.y < hi.y && lo.z < hi.z
                   ? nullptr
                   : "box corners must be finite with lo < hi on every axis";
    }

    // Faces: 0 = -x, 1 = +x, 2 = -y, 3 = +y, 4 = -z, 5 = +z.
    Bounds3 bounds() const { return {lo, hi}; }
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const;
    Vec3 normal(const Vec3& p, uint16_t face) const;
    void describe(JsonWriter& json) const { json.key("min").vec(lo, 3).key("max").vec(hi, 3); }
};

}  // namespace csg
