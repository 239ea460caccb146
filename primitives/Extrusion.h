// A 2-D region (an Outline) lifted into space: OpenSCAD's 2-D shapes, linear_extrude and
// rotate_extrude. Each is the preimage of the region under a map F from space to the plane,
//   Plane   F(x, y, z) = (x, y)                        an infinite prism: a 2-D shape
//   Linear  F(x, y, z) = (x, y) / s(z), z in [z0, z1]  s(z) = 1 + (scale - 1)(z - z0)/(z1 - z0)
//           or, with a twist or a scale per axis, R(twist s) S(s)^-1 (x, y) (TwistedExtrusion.h)
//   Rotate  F(x, y, z) = (sqrt(x^2 + y^2), z)          within the wedge 0 <= azimuth <= angle
// and a preimage commutes with union, intersection and difference. So the language keeps a
// 2-D shape as a CSG tree of Plane leaves, and extruding it lifts every leaf, leaving the
// tree as it is: the extrusion of a 2-D boolean is the 3-D boolean of the extruded leaves,
// exactly (io/Shapes2D.h).
//
// Spans, exactly:
//   Plane, Linear with scale 1: the line's projection o.xy + t d.xy crosses the outline
//     (Outline.h: watertight parity), cut by the z slab.
//   Linear with scale != 1: (x, y, z - z0) -> (x, y, z - z0) / s(z) is a projective map that
//     takes the frustum to a straight prism of height h / scale and lines to lines; the
//     line's parameter maps by a Moebius function, monotone where s > 0 (the whole slab).
//     scale = 0 makes an apex; the prism is then unbounded.
//   Linear with a twist or sx != sy: each segment's swept surface is crossed where a
//     transcendental function of t vanishes; its roots are isolated with proven enclosures
//     and the gaps between them classified at their midpoints (TwistedExtrusion.h). A
//     level line (d.z = 0) meets one section, an affine image of the outline: a prism's line.
//   Rotate: the line's image (r(t), z(t)) has r^2 quadratic in t. A straight profile edge
//     sweeps a cone (a quadratic in t), an arc a torus (a quartic), a Bezier of degree k a
//     surface met at the roots of a polynomial of degree 2k in the curve's parameter. These
//     candidate crossings are sorted and each gap between them is classified by the region's
//     point test at its midpoint, so a double or spurious root cannot flip inside and
//     outside. A wedge (angle < 360) intersects the result.
//
// Faces: 0 the bottom (z0), 1 the top (z1), 2 the wedge's start plane, 3 its end plane, and
// kFirstSideFace + (segment mod kSideFaceIds) the surface swept by an outline segment; in
// outlines of more segments normal() takes the nearest segment of that residue.
#pragma once

#include <memory>

#include "primitives/Outline.h"
#include "primitives/Primitive.h"
#include "primitives/TwistedExtrusion.h"

namespace csg {

struct Extrusion {
    static constexpr const char* kName = "extrusion";
    static constexpr uint16_t kBottomFace = 0, kTopFace = 1, kWedgeStartFace = 2, kWedgeEndFace = 3,
                              kFirstSideFace = 4;
    static constexpr uint32_t kSideFaceIds = 65535 - kFirstSideFace;

    enum class Kind : uint8_t { Plane, Linear, Rotate };

    std::shared_ptr<const Outline> outline;  // shared, immutable
    Bounds2 box;                             // the outline's bounds
    // What the language called it ("square", "circle", "polygon", "text", ...), for info.
    const char* shape = "polygon";
    // How exactly the outline stands for what the language asked, when that needs saying (a
    // projection of meshed leaves): a static text info prints as "accuracy"; null: exact.
    const char* accuracy = nullptr;
    Kind kind = Kind::Plane;
    double z0 = -kInfinity, z1 = kInfinity;  // Linear
    Vec2 scale{1.0};       // Linear: the top's size relative to the bottom's, per axis
    double twist = 0.0;    // Linear: degrees over the height, positive clockwise seen from +z
    double angle = 360.0;  // Rotate: degrees, in (0, 360]
    // Linear with a twist or sx != sy: the outline's carriers (shared, immutable).
    std::shared_ptr<const TwistedOutline> twisted;

    // A 2-D shape: the infinite prism over the outline.
    static Extrusion plane(std::shared_ptr<const Outline> outline, const char* shape);
    // The same region lifted differently (the outline is shared): the section at height
    // fraction s is the outline turned by -twist s degrees, then scaled by 1 + (scale - 1) s
    // per axis (OpenSCAD's linear_extrude).
    Extrusion linear(double bottom, double top, Vec2 topScale, double twistDegrees = 0.0) const;
    // Revolved about z: the region's part in x >= 0 (the caller mirrors a profile in x <= 0
    // and refuses one on both sides, as OpenSCAD does).
    Extrusion rotated(double degrees) const;

    const char* invalidReason() const;
    Bounds3 bounds() const;
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const;
    Vec3 normal(const Vec3& p, uint16_t face) const;
    void describe(JsonWriter& json) const;

private:
    void prismSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    void frustumSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    void revolvedSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    void twistSpans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    TwistMap twistMap() const;
    // The segment of face `face` nearest to q (see the faces above).
    uint32_t segmentOf(uint16_t face, Vec2 q) const;
};

}  // namespace csg
