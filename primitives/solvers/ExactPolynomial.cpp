// Notation: a DD value is hi + lo with |lo| <= ulp(hi) / 2 (a double-double), built from the
// error-free transformations of ErrorFree.h.
#include "primitives/solvers/ExactPolynomial.h"

#include <cassert>
#include <cmath>

#include "primitives/solvers/ErrorFree.h"

namespace csg {

ExactPolynomial::DD ExactPolynomial::add(DD a, DD b) {
    const Sum2 s = twoSum(a.hi, b.hi);
    const Sum2 r = twoSum(s.hi, s.lo + (a.lo + b.lo));
    return {r.hi, r.lo};
}

ExactPolynomial::DD ExactPolynomial::mul(DD a, DD b) {
    const Sum2 p = twoProduct(a.hi, b.hi);
    const Sum2 r = twoSum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
    return {r.hi, r.lo};
}

ExactPolynomial::ExactPolynomial() : c_(size_t(kSide) * kSide * kSide) {}

ExactPolynomial ExactPolynomial::constant(double value) {
    return monomial(value, 0, 0, 0);
}

ExactPolynomial ExactPolynomial::variable(int axis) {
    assert(axis >= 0 && axis < 3);
    return monomial(1.0, axis == 0, axis == 1, axis == 2);
}

ExactPolynomial ExactPolynomial::monomial(double c, int i, int j, int k) {
    assert(i >= 0 && j >= 0 && k >= 0 && i + j + k <= kMaxDegree);
    ExactPolynomial p;
    p.c_[index(i, j, k)] = {c, 0.0};
    return p;
}

int ExactPolynomial::degree() const {
    int d = 0;
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; i + j < kSide; ++j)
            for (int k = 0; i + j + k < kSide; ++k)
                if (c_[index(i, j, k)].hi != 0.0) d = std::max(d, i + j + k);
    return d;
}

bool ExactPolynomial::isZero() const {
    for (const DD& v : c_)
        if (v.hi != 0.0) return false;
    return true;
}

double ExactPolynomial::coefficient(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i + j + k > kMaxDegree) return 0.0;
    const DD& v = c_[index(i, j, k)];
    return v.hi + v.lo;
}

ExactPolynomial operator+(const ExactPolynomial& a, const ExactPolynomial& b) {
    ExactPolynomial r;
    for (size_t i = 0; i < r.c_.size(); ++i) r.c_[i] = ExactPolynomial::add(a.c_[i], b.c_[i]);
    return r;
}

ExactPolynomial ExactPolynomial::operator-() const {
    ExactPolynomial r = *this;
    for (DD& v : r.c_) v = {-v.hi, -v.lo};
    return r;
}

ExactPolynomial operator-(const ExactPolynomial& a, const ExactPolynomial& b) {
    return a + (-b);
}

std::optional<ExactPolynomial> ExactPolynomial::times(const ExactPolynomial& b) const {
    const int da = degree(), db = b.degree();
    if (da + db > kMaxDegree) return std::nullopt;
    ExactPolynomial r;
    // Step: every pair of nonzero terms, accumulated in double-double.
    for (int i = 0; i <= da; ++i)
        for (int j = 0; i + j <= da; ++j)
            for (int k = 0; i + j + k <= da; ++k) {
                const DD u = c_[index(i, j, k)];
                if (u.hi == 0.0) continue;
                for (int p = 0; p <= db; ++p)
                    for (int q = 0; p + q <= db; ++q)
                        for (int s = 0; p + q + s <= db; ++s) {
                            const DD v = b.c_[index(p, q, s)];
                            if (v.hi == 0.0) continue;
                            DD& t = r.c_[index(i + p, j + q, k + s)];
                            t = add(t, mul(u, v));
                        }
            }
    return r;
}

std::optional<ExactPolynomial> ExactPolynomial::power(int k) const {
    if (k < 0) return std::nullopt;
    if (k == 0) return constant(1.0);
    if (isZero()) return *this;
    if (degree() * k > kMaxDegree) return std::nullopt;
    ExactPolynomial r = *this;
    for (int i = 1; i < k; ++i) r = *r.times(*this);
    return r;
}

std::optional<ExactPolynomial> ExactPolynomial::dividedBy(double v) const {
    if (!(v != 0.0) || !std::isfinite(v)) return std::nullopt;
    ExactPolynomial r = *this;
    for (DD& c : r.c_) {
        // Double-double by double: a quotient and one correction step from the exact
        // remainder (fma).
        const double q1 = c.hi / v;
        const double rem = std::fma(-q1, v, c.hi) + c.lo;
        const double q2 = rem / v;
        const Sum2 q = twoSum(q1, q2);
        c = {q.hi, q.lo};
    }
    return r;
}

ExactPolynomial ExactPolynomial::shifted(const Vec3& c) const {
    ExactPolynomial r = *this;
    const int n = degree();
    // Step: for each axis, every fibre of coefficients along it is a univariate polynomial;
    // shift it by c[axis] with repeated synthetic division (n^2 / 2 double-double steps).
    for (int axis = 0; axis < 3; ++axis) {
        if (c[axis] == 0.0) continue;
        const DD s{c[axis], 0.0};
        for (int u = 0; u <= n; ++u)
            for (int v = 0; u + v <= n; ++v) {
                auto at = [&](int e) -> DD& {
                    return axis == 0   ? r.c_[index(e, u, v)]
                           : axis == 1 ? r.c_[index(u, e, v)]
                                       : r.c_[index(u, v, e)];
                };
                const int m = n - u - v;  // the fibre's degree
                for (int k = 0; k < m; ++k)
                    for (int i = m - 1; i >= k; --i) at(i) = add(at(i), mul(at(i + 1), s));
            }
    }
    return r;
}

Trivariate ExactPolynomial::toTrivariate() const {
    const int n = degree();
    Trivariate t(n);
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j)
            for (int k = 0; i + j + k <= n; ++k) t.at(i, j, k) = coefficient(i, j, k);
    return t;
}

}  // namespace csg
