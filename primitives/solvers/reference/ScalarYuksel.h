// Yuksel's method (critical points bracket the roots, recursively; HPG 2022) written once for
// any scalar T, so the accuracy report can time float against double on the *same* code: the
// only difference between the two rows is the type. Report-only: production solves in double
// (primitives/solvers/Yuksel.cpp, which adds the tangency and cluster handling of Roots.h that
// this sketch leaves out; the report's classes have no tangencies, so the comparison is fair).
//
// Notation: c[0..n] are ascending coefficients, p(t) = sum c[i] t^i; roots in [lo, hi].
#pragma once

#include <algorithm>
#include <cmath>

namespace csg {

template <class T>
T hornerT(const T* c, int n, T t) {
    T y = c[n];
    for (int i = n - 1; i >= 0; --i) y = std::fma(y, t, c[i]);
    return y;
}

// The root of p in [lo, hi] where p(lo), p(hi) differ in sign: Newton kept inside the
// bracket, bisection otherwise, until the bracket is two adjacent values of T.
template <class T>
T refineT(const T* c, int n, T lo, T hi) {
    const bool risingAtLo = hornerT(c, n, lo) < T(0);
    T x = lo / 2 + hi / 2;
    for (int it = 0; it < 200; ++it) {
        T v = c[n], dv = T(0);
        for (int i = n - 1; i >= 0; --i) {
            dv = std::fma(dv, x, v);
            v = std::fma(v, x, c[i]);
        }
        if (v == T(0)) return x;
        ((v < T(0)) == risingAtLo ? lo : hi) = x;
        T next = dv != T(0) ? x - v / dv : lo;
        if (!(next > lo && next < hi)) next = lo / 2 + hi / 2;
        if (next == x || next <= lo || next >= hi) return x;
        x = next;
    }
    return x;
}

// Real roots of c[0..n] (n <= 16) in [lo, hi], ascending, each crossing once; returns the count.
template <class T>
int yukselRootsT(const T* c, int n, T lo, T hi, T* out) {
    while (n > 0 && c[n] == T(0)) --n;
    if (n <= 0) return 0;
    if (n == 1) {
        const T r = -c[0] / c[1];
        return r >= lo && r <= hi ? (out[0] = r, 1) : 0;
    }
    // Step 1: the critical points, from the derivative's roots (recursively).
    T dc[16], x[18];
    for (int i = 1; i <= n; ++i) dc[i - 1] = T(i) * c[i];
    int k = 0;
    x[k++] = lo;
    T crit[16];
    const int nc = yukselRootsT(dc, n - 1, lo, hi, crit);
    for (int i = 0; i < nc; ++i)
        if (crit[i] > x[k - 1] && crit[i] < hi) x[k++] = crit[i];
    x[k++] = hi;
    // Step 2: p is monotone between neighbours: a sign change brackets one root.
    int m = 0;
    T prev = hornerT(c, n, x[0]);
    if (prev == T(0)) out[m++] = x[0];
    for (int i = 1; i < k; ++i) {
        const T v = hornerT(c, n, x[i]);
        if (v == T(0))
            out[m++] = x[i];
        else if (prev != T(0) && (prev < T(0)) != (v < T(0)))
            out[m++] = refineT(c, n, x[i - 1], x[i]);
        prev = v;
    }
    return m;
}

}  // namespace csg
