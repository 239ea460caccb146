// A solid ring torus centred at the local origin around the z axis (OpenSCAD's
// rotate_extrude() of circle(r) translated by R): (sqrt(x^2 + y^2) - R)^2 + z^2 <= r^2.
// Requires R > r > 0 (a spindle torus, r >= R, is not this solid's quartic).
#pragma once

#include "primitives/Primitive.h"
#include "primitives/solvers/Polynomial.h"
#include "primitives/solvers/Solve.h"

namespace csg {

struct Torus {
    static constexpr const char* kName = "torus";

    double majorRadius = 1.0;   // R: from the z axis to the tube's centre circle
    double minorRadius = 0.25;  // r: the tube's radius
    // Auto: the tube form (rho - R)^2 + z^2 - r^2 on its monotone pieces (Torus.cpp); any
    // other: the quartic by that solver (for comparisons).
    Solver solver = Solver::Auto;
    // How crossings are refined after isolation (Polish.h) against the exact root for the local
    // line's doubles: Auto, where the tube form's rounding bound over |G'| may exceed half an
    // ulp of t, by one Newton step on G evaluated in double-double (the quartic path: Newton on
    // quarticDD); Newton, Laguerre, Bairstow on every crossing, on quarticDD; None: the
    // isolating path's own answer.
    Polisher polisher = Polisher::Auto;

    const char* invalidReason() const {
        return std::isfinite(majorRadius) && minorRadius > 0.0 && majorRadius > minorRadius
                   ? nullptr
                   : "torus needs R > r > 0 (a spindle or horn torus is not supported)";
    }

    // Tight: [-R-r, R+r]^2 x [-r, r].
    Bounds3 bounds() const {
        const double e = majorRadius + minorRadius;
        return {Vec3(-e, -e, -minorRadius), Vec3(e, e, minorRadius)};
    }
    // Up to 2 spans (face 0, the torus surface); a tangent ray gives a zero-length span.
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const;
    // (p - c) / |p - c| with c the nearest point of the centre circle (the gradient of the
    // distance to the tube); on the axis or the centre circle itself, +z.
    Vec3 normal(const Vec3& p, uint16_t face) const;
    void describe(JsonWriter& json) const {
        json.key("R").value(majorRadius).key("r").value(minorRadius);
    }

    // The torus quartic along o + s u, |u| = 1, solved as is (no origin shift, no bounding
    // test): exposed so tests can show what moving the origin is worth.
    Polynomial quarticAlong(const Vec3& o, const Vec3& u) const;
    // The torus quartic along o + (tBase + sigma) d as a polynomial in sigma, formed from the
    // doubles o, d, tBase, R and r in double-double: what the polish solves.
    PolynomialDD quarticDD(const Vec3& o, const Vec3& d, double tBase) const;
};

}  // namespace csg
