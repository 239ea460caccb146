// The implicit equation of the curve that carries an outline segment (primitives/Outline.h),
// homogeneous in (X, Y, W): the profile point q = (X, Y) / W, W > 0, lies on the carrier iff
// F(X, Y, W) = 0. Twisted extrusions (primitives/TwistedExtrusion.h) feed it a line's image,
// which is a curve in homogeneous coordinates, and isolate the zeros of F along it.
//
//   Line       F = L                          L the affine form of the line through the ends
//   Ellipse    F = U^2 + V^2 - det^2 W^2      U, V = adj(axes) (q - centre) W, scaled by det
//   Parabola   F = L1^2 - 4 L0 L2             L_i = twice the barycentric coordinates' areas
//                                             in the control triangle (a quadratic Bezier)
//   Cubic      F = det of Sederberg's 3x3 Bezout matrix of the cubic Bezier, entries the
//              forms l_ij = C(3,i) C(3,j) det[X Y W; x_i y_i 1; x_j y_j 1]
//
// Every form is affine in (X, Y, W) and none divides, so F is a polynomial of degree 1, 2 or 3.
// The forms' coefficients are kept as intervals that enclose the exact coefficients of the
// segment's doubles (computed in outward-rounded interval arithmetic), so an enclosure of F
// evaluated from them encloses the exact F; their midpoints serve point evaluation (Newton).
// The carrier holds the whole curve (the whole line, ellipse, parabola or cubic curve); the
// segment's box tells which of its points may be on the segment.
//
// Degenerate segments: a Bezier flatter than tol::kFlatCurveRel is carried by its line (its
// implicit equation would be a power of the line's, with no sign change), a cubic that is a
// quadratic by its parabola, an ellipse with parallel axes by the line it collapses onto, and a
// segment of no extent by nothing (kind None: it bounds nothing).
#pragma once

#include <array>
#include <cstdint>

#include "primitives/Outline.h"
#include "primitives/solvers/Interval.h"

namespace csg {

struct SegmentCarrier {
    enum class Kind : uint8_t { None, Line, Ellipse, Parabola, Cubic };
    Kind kind = Kind::None;
    // The segment's box: its ends, its control points or its arc's (arcBox in the .cpp).
    Bounds2 box;
    // Affine forms a X + b Y + c W, three coefficients each: Line 1 form, Ellipse 2 (U, V) and
    // det^2 in the next slot, Parabola 3 (L0, L1, L2), Cubic 6 (l10, l20, l30, l21, l31, l32).
    std::array<Interval, 18> coef{};
    std::array<double, 18> mid{};

    static SegmentCarrier of(const Segment2& segment);
};

// F and its gradient (dF/dX, dF/dY, dF/dW) at (X, Y, W), and the second derivative of F
// along a direction, e^T Hess(F) e at (X, Y, W) with e = (dx, dy, dw): T = double evaluates with
// the coefficients' midpoints, T = Interval encloses the exact values over the given
// intervals. Inline: they run in the innermost loop of a twisted extrusion's spans.
template <class T>
T carrierValue(const SegmentCarrier& c, T x, T y, T w);
template <class T>
void carrierGradient(const SegmentCarrier& c, T x, T y, T w, T gradient[3]);
template <class T>
T carrierCurvature(const SegmentCarrier& c, T x, T y, T w, T dx, T dy, T dw);

namespace carrier_detail {

// A constant, and the square, for either scalar.
template <class T>
T constant(double v);
template <>
inline double constant<double>(double v) {
    return v;
}
template <>
inline Interval constant<Interval>(double v) {
    return pointInterval(v);
}
inline double sqr(double v) {
    return v * v;
}
using csg::sqr;

template <class T>
T coefficient(const SegmentCarrier& c, int i);
template <>
inline double coefficient<double>(const SegmentCarrier& c, int i) {
    return c.mid[i];
}
template <>
inline Interval coefficient<Interval>(const SegmentCarrier& c, int i) {
    return c.coef[i];
}

// Form k (coefficients 3k, 3k + 1, 3k + 2) at (x, y, w).
template <class T>
T form(const SegmentCarrier& c, int k, T x, T y, T w) {
    return coefficient<T>(c, 3 * k) * x + coefficient<T>(c, 3 * k + 1) * y +
           coefficient<T>(c, 3 * k + 2) * w;
}

// gradient += factor * (gradient of form k).
template <class T>
void addForm(const SegmentCarrier& c, int k, T factor, T gradient[3]) {
    for (int i = 0; i < 3; ++i) gradient[i] = gradient[i] + factor * coefficient<T>(c, 3 * k + i);
}

// The cubic's symmetric Bezout matrix: m00 = l32, m01 = l31, m02 = l30, m11 = l30 + l21,
// m12 = l20, m22 = l10 (forms 0..5 are l10, l20, l30, l21, l31, l32), and its cofactors.
template <class T>
struct Bezout {
    T m00, m01, m02, m11, m12, m22;
    T c00, c01, c02, c11, c12, c22;
    Bezout(const SegmentCarrier& c, T x, T y, T w) {
        const T l10 = form(c, 0, x, y, w), l20 = form(c, 1, x, y, w), l30 = form(c, 2, x, y, w);
        const T l21 = form(c, 3, x, y, w), l31 = form(c, 4, x, y, w), l32 = form(c, 5, x, y, w);
        m00 = l32, m01 = l31, m02 = l30, m11 = l30 + l21, m12 = l20, m22 = l10;
        c00 = m11 * m22 - m12 * m12;
        c01 = m12 * m02 - m01 * m22;
        c02 = m01 * m12 - m11 * m02;
        c11 = m00 * m22 - m02 * m02;
        c12 = m01 * m02 - m00 * m12;
        c22 = m00 * m11 - m01 * m01;
    }
};

}  // namespace carrier_detail

template <class T>
T carrierValue(const SegmentCarrier& c, T x, T y, T w) {
    using namespace carrier_detail;
    switch (c.kind) {
        case SegmentCarrier::Kind::Line: return form(c, 0, x, y, w);
        case SegmentCarrier::Kind::Ellipse: {
            const T u = form(c, 0, x, y, w), v = form(c, 1, x, y, w);
            return sqr(u) + sqr(v) - coefficient<T>(c, 6) * sqr(w);
        }
        case SegmentCarrier::Kind::Parabola: {
            const T l0 = form(c, 0, x, y, w), l1 = form(c, 1, x, y, w), l2 = form(c, 2, x, y, w);
            return sqr(l1) - 4.0 * (l0 * l2);
        }
        case SegmentCarrier::Kind::Cubic: {
            const Bezout<T> b(c, x, y, w);
            return b.m00 * b.c00 + b.m01 * b.c01 + b.m02 * b.c02;
        }
        case SegmentCarrier::Kind::None: break;
    }
    return constant<T>(1.0);
}

template <class T>
void carrierGradient(const SegmentCarrier& c, T x, T y, T w, T gradient[3]) {
    using namespace carrier_detail;
    gradient[0] = gradient[1] = gradient[2] = constant<T>(0.0);
    switch (c.kind) {
        case SegmentCarrier::Kind::Line: addForm(c, 0, constant<T>(1.0), gradient); return;
        case SegmentCarrier::Kind::Ellipse: {
            addForm(c, 0, 2.0 * form(c, 0, x, y, w), gradient);
            addForm(c, 1, 2.0 * form(c, 1, x, y, w), gradient);
            gradient[2] = gradient[2] - 2.0 * (coefficient<T>(c, 6) * w);
            return;
        }
        case SegmentCarrier::Kind::Parabola: {
            const T l0 = form(c, 0, x, y, w), l1 = form(c, 1, x, y, w), l2 = form(c, 2, x, y, w);
            addForm(c, 1, 2.0 * l1, gradient);
            addForm(c, 0, -4.0 * l2, gradient);
            addForm(c, 2, -4.0 * l0, gradient);
            return;
        }
        case SegmentCarrier::Kind::Cubic: {
            // d det = sum_ij C_ij dm_ij; the off-diagonal entries appear twice.
            const Bezout<T> b(c, x, y, w);
            addForm(c, 5, b.c00, gradient);                  // m00 = l32
            addForm(c, 4, 2.0 * b.c01, gradient);            // m01 = l31
            addForm(c, 2, 2.0 * b.c02 + b.c11, gradient);    // m02 = l30, and in m11
            addForm(c, 3, b.c11, gradient);                  // m11 = l30 + l21
            addForm(c, 1, 2.0 * b.c12, gradient);            // m12 = l20
            addForm(c, 0, b.c22, gradient);                  // m22 = l10
            return;
        }
        case SegmentCarrier::Kind::None: return;
    }
}

template <class T>
T carrierCurvature(const SegmentCarrier& c, T x, T y, T w, T dx, T dy, T dw) {
    using namespace carrier_detail;
    switch (c.kind) {
        case SegmentCarrier::Kind::Line: return constant<T>(0.0);
        case SegmentCarrier::Kind::Ellipse: {
            // The forms are linear, so along e they change by their value at e.
            const T du = form(c, 0, dx, dy, dw), dv = form(c, 1, dx, dy, dw);
            return 2.0 * (sqr(du) + sqr(dv) - coefficient<T>(c, 6) * sqr(dw));
        }
        case SegmentCarrier::Kind::Parabola: {
            const T d0 = form(c, 0, dx, dy, dw), d1 = form(c, 1, dx, dy, dw),
                    d2 = form(c, 2, dx, dy, dw);
            return 2.0 * sqr(d1) - 8.0 * (d0 * d2);
        }
        case SegmentCarrier::Kind::Cubic: {
            // For 3x3 matrices det(M + s A) = det M + s tr(adj(M) A) + s^2 tr(adj(A) M) +
            // s^3 det A, so the second derivative at s = 0 is 2 tr(adj(A) M), A the Bezout
            // matrix of the forms at e (its rate along e); both are symmetric.
            const Bezout<T> m(c, x, y, w), a(c, dx, dy, dw);
            const T trace = a.c00 * m.m00 + a.c11 * m.m11 + a.c22 * m.m22 +
                            2.0 * (a.c01 * m.m01 + a.c02 * m.m02 + a.c12 * m.m12);
            return 2.0 * trace;
        }
        case SegmentCarrier::Kind::None: break;
    }
    return constant<T>(0.0);
}

}  // namespace csg
