// Test and benchmark helpers for the algebraic patch methods: patches built from a polynomial
// map (exact degree elevation to Bernstein form), the article-style patches, random patches,
// and a 50-digit reference for a crossing (Newton on S(u, v) - o - t d = 0 in
// Boost.Multiprecision from a double guess), independent of any method's plane choice.
#pragma once

#include <array>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <random>
#include <utility>

#include "primitives/patch/BezierPatch.h"

namespace csg::patchref {

using Big = boost::multiprecision::cpp_bin_float_50;

// The patch of S(u, v) = sum a[k][l] u^k v^l (bidegree <= (3, 3)): monomial to Bernstein,
// u^k = sum_{i >= k} C(i, k) / C(3, k) B_i(u). Exact for dyadic inputs.
inline BezierPatch fromMonomials(const std::array<std::array<Vec3, 4>, 4>& a) {
    static constexpr double C[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            Vec3 s(0.0);
            for (int k = 0; k <= i; ++k)
                for (int l = 0; l <= j; ++l) s += C[i][k] / C[3][k] * C[j][l] / C[3][l] * a[k][l];
            p.points[4 * i + j] = s;
        }
    return p;
}

// The article-style patches of increasing generality, all linear in v (ruled): kind 1, a
// bilinear (twisted quadrilateral) patch; kind 2, ruled between two quadratic curves; kind 3,
// ruled between two cubic curves. A line meets them 2, 4 and 6 times over C: the eliminant's
// u-degree. Coefficients are fixed, dyadic, and chosen so that no special alignment occurs.
// articleMonomials gives the monomial coefficients a[k][l] of u^k v^l.
inline std::array<std::array<Vec3, 4>, 4> articleMonomials(int kind) {
    std::array<std::array<Vec3, 4>, 4> a{};
    a[0][0] = Vec3(0.0, 0.0, 0.0);
    a[1][0] = Vec3(1.0, 0.125, 0.25);
    a[0][1] = Vec3(0.0625, 1.0, -0.125);
    a[1][1] = Vec3(0.25, -0.375, 0.75);
    if (kind >= 2) {
        a[2][0] = Vec3(-0.25, 0.5, -0.625);
        a[2][1] = Vec3(0.375, 0.25, 0.5);
    }
    if (kind >= 3) {
        a[3][0] = Vec3(0.5, -0.25, 0.875);
        a[3][1] = Vec3(-0.125, 0.625, -0.375);
    }
    return a;
}
inline BezierPatch articlePatch(int kind) {
    return fromMonomials(articleMonomials(kind));
}

// The patch of the monomial map a, degree-elevated exactly when every a[k][l] is 9 times a
// dyadic number (the elevation divides by C(3, k) C(3, l) in {1, 3, 9}): each control point
// is a sum of dyadic terms, so the patch has exactly the bidegree of a (fromMonomials rounds
// 1/3, which leaves residue of 1e-17 in the higher coefficients).
inline BezierPatch fromMonomialsExactly(const std::array<std::array<Vec3, 4>, 4>& a) {
    static constexpr double C[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            Vec3 s(0.0);
            for (int k = 0; k <= i; ++k)
                for (int l = 0; l <= j; ++l)
                    s += (C[i][k] * C[j][l] * a[k][l]) / (C[3][k] * C[3][l]);
            p.points[4 * i + j] = s;
        }
    return p;
}

// The article-style patch of the given kind scaled by 9 and elevated exactly: a patch of
// exactly bidegree (kind, 1), for the exact methods.
inline BezierPatch exactArticlePatch(int kind) {
    std::array<std::array<Vec3, 4>, 4> a = articleMonomials(kind);
    for (auto& row : a)
        for (Vec3& c : row) c *= 9.0;
    return fromMonomialsExactly(a);
}

// A patch with control points uniform in [-1, 1]^3 plus a gentle base surface, so that it is
// a sheet rather than a knot and random rays through its box hit it a few times.
inline BezierPatch randomPatch(std::mt19937_64& rng, double roughness = 0.5) {
    std::uniform_real_distribution<double> jitter(-roughness, roughness);
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            p.points[4 * i + j] = Vec3(i / 1.5 - 1.0 + 0.3 * jitter(rng),
                                       j / 1.5 - 1.0 + 0.3 * jitter(rng), 2.0 * jitter(rng));
    return p;
}

// A ray from outside the patch's box towards a random point of the box (o near the patch, as
// the contract of BezierPatch.h assumes).
inline void randomRay(std::mt19937_64& rng, const BezierPatch& patch, Vec3& o, Vec3& d) {
    const Bounds3 b = patch.hullBounds();
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> gauss;
    const Vec3 target = b.lo + Vec3(unit(rng), unit(rng), unit(rng)) * (b.hi - b.lo);
    Vec3 dir(gauss(rng), gauss(rng), gauss(rng));
    dir = glm::normalize(dir);
    const double reach = glm::length(b.hi - b.lo);
    o = target - reach * dir;
    d = dir * (0.5 + unit(rng));  // not unit length, as in the contract
}

template <typename T>
std::array<T, 4> bernstein(const T& x) {
    const T y = 1 - x;
    return {y * y * y, 3 * x * y * y, 3 * x * x * y, x * x * x};
}
template <typename T>
std::array<T, 4> bernsteinDerivative(const T& x) {
    const T y = 1 - x;
    return {-3 * y * y, 3 * y * (y - 2 * x), 3 * x * (2 * y - x), 3 * x * x};
}

// The crossing nearest (u, v, t) in 50 digits: Newton on G(u, v, t) = S(u, v) - o - t d (3
// equations, 3 unknowns), from the doubles. False when it does not converge (a tangent ray).
inline bool refine(const BezierPatch& patch, const Vec3& o, const Vec3& d, double& u, double& v,
                   Big& t) {
    Big U = u, V = v, T = t;
    for (int it = 0; it < 60; ++it) {
        const auto bu = bernstein(U), bv = bernstein(V);
        const auto du = bernsteinDerivative(U), dv = bernsteinDerivative(V);
        Big g[3], su[3], sv[3];
        for (int c = 0; c < 3; ++c) {
            g[c] = su[c] = sv[c] = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) {
                    const Big p = patch.at(i, j)[c];
                    g[c] += bu[i] * bv[j] * p;
                    su[c] += du[i] * bv[j] * p;
                    sv[c] += bu[i] * dv[j] * p;
                }
            g[c] -= Big(o[c]) + T * Big(d[c]);
        }
        // Solve [su sv -d] x = -g by Cramer's rule.
        const Big m[3][3] = {
            {su[0], sv[0], -Big(d[0])}, {su[1], sv[1], -Big(d[1])}, {su[2], sv[2], -Big(d[2])}};
        auto det3 = [](const Big a[3][3]) {
            return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                   a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                   a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        };
        const Big det = det3(m);
        if (det == 0) return false;
        Big x[3];
        for (int k = 0; k < 3; ++k) {
            Big mk[3][3];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) mk[r][c] = c == k ? -g[r] : m[r][c];
            x[k] = det3(mk) / det;
        }
        U += x[0];
        V += x[1];
        T += x[2];
        if (abs(x[0]) + abs(x[1]) < Big(1e-40)) {
            u = double(U);
            v = double(V);
            t = T;
            return true;
        }
    }
    return false;
}

// Independent oracle for a patch linear in v, S(u, v) = A(u) + v B(u) (the article-style
// patches): the line meets it where A(u) - o, B(u) and d are coplanar, det[A - o, B, d] = 0, a
// polynomial in u of degree <= 6 here. Its sign changes on a 4096-sample grid of [-1e-6, 1 + 1e-6]
// are bisected in 50 digits; v is the least-squares solution of (A - o + v B) x d = 0, kept in
// [0, 1]; t follows. Tangent (double) roots are missed: callers skip rays that graze.
inline int ruledCrossings(const BezierPatch& patch, const Vec3& o, const Vec3& d, double* ts,
                          double* us, double* vs) {
    auto curves = [&](const Big& u, Big A[3], Big B[3]) {
        const auto bu = bernstein(u);
        for (int c = 0; c < 3; ++c) {
            Big a = 0, b = 0;
            for (int i = 0; i < 4; ++i) {
                // S(u, v) along v is linear: the row's v = 0 and v = 1 ends.
                a += bu[i] * Big(patch.at(i, 0)[c]);
                b += bu[i] * (Big(patch.at(i, 3)[c]) - Big(patch.at(i, 0)[c]));
            }
            A[c] = a - Big(o[c]);
            B[c] = b;
        }
    };
    auto det = [&](const Big& u) {
        Big A[3], B[3];
        curves(u, A, B);
        const Big D[3] = {d.x, d.y, d.z};
        return A[0] * (B[1] * D[2] - B[2] * D[1]) - A[1] * (B[0] * D[2] - B[2] * D[0]) +
               A[2] * (B[0] * D[1] - B[1] * D[0]);
    };
    int n = 0;
    const int kSamples = 4096;
    const Big lo = Big(-1e-6), w = Big(1) + Big(2e-6);
    Big prevU = lo, prev = det(lo);
    for (int k = 1; k <= kSamples; ++k) {
        const Big u = lo + w * k / kSamples;
        const Big cur = det(u);
        if ((prev < 0) != (cur < 0) || cur == 0) {
            Big a = prevU, b = u, fa = prev;
            for (int it = 0; it < 170; ++it) {
                const Big m = (a + b) / 2, fm = det(m);
                if ((fm < 0) == (fa < 0)) {
                    a = m;
                    fa = fm;
                } else {
                    b = m;
                }
            }
            const Big ur = (a + b) / 2;
            Big A[3], B[3];
            curves(ur, A, B);
            const Big D[3] = {d.x, d.y, d.z};
            Big ax[3], bx[3];
            for (int c = 0; c < 3; ++c) {
                ax[c] = A[(c + 1) % 3] * D[(c + 2) % 3] - A[(c + 2) % 3] * D[(c + 1) % 3];
                bx[c] = B[(c + 1) % 3] * D[(c + 2) % 3] - B[(c + 2) % 3] * D[(c + 1) % 3];
            }
            const Big vr = -(ax[0] * bx[0] + ax[1] * bx[1] + ax[2] * bx[2]) /
                           (bx[0] * bx[0] + bx[1] * bx[1] + bx[2] * bx[2]);
            if (ur >= 0 && ur <= 1 && vr >= 0 && vr <= 1) {
                Big tr = 0, dd = 0;
                const Big D2[3] = {d.x, d.y, d.z};
                for (int c = 0; c < 3; ++c) {
                    tr += D2[c] * (A[c] + vr * B[c]);
                    dd += D2[c] * D2[c];
                }
                ts[n] = double(tr / dd);
                us[n] = double(ur);
                vs[n] = double(vr);
                ++n;
            }
        }
        prevU = u;
        prev = cur;
    }
    for (int i = 1; i < n; ++i)  // ascending in t, as the methods list them
        for (int k = i; k > 0 && ts[k] < ts[k - 1]; --k) {
            std::swap(ts[k], ts[k - 1]);
            std::swap(us[k], us[k - 1]);
            std::swap(vs[k], vs[k - 1]);
        }
    return n;
}

}  // namespace csg::patchref
