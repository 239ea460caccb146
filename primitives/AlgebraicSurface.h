// An algebraic solid: { p in box : F(p) <= 0 }, F a trivariate polynomial of total degree
// 1..16 (OpenSCAD-style surface(f = "...", bbox = [[x0,y0,z0],[x1,y1,z1]], solver = "auto")).
//
// Building one (the language maps an expression onto ExactPolynomial, then calls make):
//   ExactPolynomial r2 = x*x + y*y + z*z  (via ExactPolynomial::times, see its header)
//   AlgebraicSurface s = AlgebraicSurface::make(*(r2 - constant(1)).power(3), box, Solver::Auto);
//   if (const char* why = s.invalidReason()) ... report it at the DSL line
// make() does all the work once: F is re-centred at the box centre c exactly (double-double
// Taylor shift, one rounding per coefficient: G(q) = F(c + q)), scaled by a power of two to
// coefficients of magnitude <= 1 (the solid is unchanged), and its gradient is formed. The
// primitive itself is a shared pointer to that immutable data plus the per-object solver
// choice, so the Primitive variant stays small and copies are cheap.
//
// Faces: 0..5 the box's (-x, +x, -y, +y, -z, +z, as Box), 6 the surface F = 0.
#pragma once

#include <memory>

#include "primitives/Primitive.h"
#include "primitives/solvers/ExactPolynomial.h"
#include "primitives/solvers/Solve.h"
#include "primitives/solvers/Trivariate.h"

namespace csg {

struct AlgebraicData;

struct AlgebraicSurface {
    static constexpr const char* kName = "surface";
    static constexpr uint16_t kSurfaceFace = 6;

    std::shared_ptr<const AlgebraicData> data;  // null: not built (invalid)
    Solver solver = Solver::Auto;
    // 0: roots to double precision; > 0: the solvers' bracket tolerance relative to the
    // half-length of the ray's chord through the box (Solve.h), traded for time.
    double tolerance = 0.0;
    // How the isolated roots are refined (Polish.h): on the chord polynomial formed in
    // double-double from the local ray and G's own coefficients, so that a simple crossing's t
    // is within an ulp of the exact root of G(o + t d - centre) for the ray's doubles (Auto:
    // where the evaluation's and the chord coefficients' rounding bounds over |p'| exceed half an
    // ulp of t: crossingTimes). Not with tolerance > 0.
    Polisher polisher = Polisher::Auto;

    // Builds the surface (never throws; bad input shows in invalidReason()).
    static AlgebraicSurface make(const ExactPolynomial& f, const Bounds3& box,
                                 Solver solver = Solver::Auto, double tolerance = 0.0,
                                 Polisher polisher = Polisher::Auto);

    const char* invalidReason() const;
    // The box.
    Bounds3 bounds() const;
    // Up to 9 spans (16 roots cut by the box); ends are box faces 0..5 or the surface, 6. A
    // tangency (double root) neither opens nor closes a span, and neither does a pair of
    // roots that the chord polynomial's own rounding may have split from one: a thin piece
    // between two roots whose sign is within the chord's error bound (chordErrorBound) at its
    // middle and quarter points takes its neighbours' side, so an even power such as
    // (r^2 - 1)^2 or a tangent ray gives no sliver span.
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    bool inside(const Vec3& p) const;
    // Box faces: the face's axis. Surface: grad F / |grad F|; at a critical point (grad F =
    // 0, e.g. the apex of a cone x^2 + y^2 - z^2) the direction from the box centre, or +z at
    // the centre itself: defined, never NaN.
    Vec3 normal(const Vec3& p, uint16_t face) const;
    // The polynomial's degree, its box and the solver.
    void describe(JsonWriter& json) const;

    // F(o + t d) on the chord of the line through the box, as the solvers see it: the
    // polynomial in u with t = tMid + u * scale, u in [uLo, uHi] within [-1, 1]. False when
    // the line misses the box. For tests and the accuracy report.
    struct Chord {
        Polynomial poly;
        double tMid, scale, uLo, uHi, tIn, tOut;
        uint16_t faceIn, faceOut;
    };
    bool chord(const Vec3& o, const Vec3& d, Chord& c) const;
    // A bound on how far the chord polynomial's value at u (computed from q = the chord's
    // middle point relative to the box centre and hd = scale * d) may be from G(q + u hd)
    // through the rounding of its coefficients (unit: G's; not counting evaluation, which
    // Polynomial::eval bounds).
    double chordErrorBound(const Vec3& q, const Vec3& hd, double u) const;
    // The chord polynomial of c in double-double, from the line's doubles o and d: the
    // polynomial in u whose roots the polish finds (see polisher).
    PolynomialDD chordDD(const Vec3& o, const Vec3& d, const Chord& c) const;
    // The crossing times t of roots[0..n) of c.poly (Solve.h's contract), polished by polisher:
    // t[i] = tMid + u scale rounded once, u the polished root; tangencies and the roots that
    // Auto leaves are converted in double. Returns how many were polished.
    int crossingTimes(const Vec3& o, const Vec3& d, const Chord& c, const double* roots, int n,
                      double* t) const;
};

// The immutable part, shared by copies.
struct AlgebraicData {
    Bounds3 box;
    Vec3 centre;
    Trivariate g;                   // G(q) = k F(centre + q), k > 0 a power of two
    Trivariate gradient[3];         // dG/dx, dG/dy, dG/dz
    Trivariate magnitude;           // |G|: G's coefficients' magnitudes, for chord error bounds
    const char* invalid = nullptr;  // why the input is not a surface, or nullptr
};

}  // namespace csg
