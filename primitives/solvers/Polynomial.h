// A univariate polynomial of degree <= 20 with real coefficients, stored inline (no heap). 20,
// not the surfaces' 16 (Trivariate::kMaxDegree), so that every solver can be measured to degree
// 20 (the accuracy report's degree sweep, the thesis' claim about Sturm sequences above 8).
// Notation: p(t) = sum_{i=0}^{degree} c[i] t^i, coefficients ascending. The degree is nominal:
// c[degree] may be 0 until trimmed() drops exact-zero leading coefficients.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <initializer_list>

#include "primitives/base/Tolerances.h"

namespace csg {

class Polynomial {
public:
    static constexpr int kMaxDegree = 20;

    Polynomial() = default;
    // Coefficients in ascending order: {c0, c1, ..., cn} is c0 + c1 t + ... + cn t^n.
    Polynomial(std::initializer_list<double> ascending) {
        assert(ascending.size() >= 1 && int(ascending.size()) <= kMaxDegree + 1);
        degree_ = int(ascending.size()) - 1;
        std::copy(ascending.begin(), ascending.end(), c_.begin());
    }
    static Polynomial ofDegree(int degree) {
        assert(degree >= 0 && degree <= kMaxDegree);
        Polynomial p;
        p.degree_ = degree;
        return p;
    }

    int degree() const { return degree_; }
    double operator[](int i) const { return c_[i]; }
    double& operator[](int i) { return c_[i]; }
    double leading() const { return c_[degree_]; }

    // The same polynomial without exact-zero leading coefficients (degree 0 when all are 0).
    Polynomial trimmed() const {
        Polynomial q = *this;
        while (q.degree_ > 0 && q.c_[q.degree_] == 0.0) --q.degree_;
        return q;
    }

    // p(t) by Horner's rule, one fused rounding per step.
    double operator()(double t) const {
        double y = c_[degree_];
        for (int i = degree_ - 1; i >= 0; --i) y = std::fma(y, t, c_[i]);
        return y;
    }

    // p(t) with a running bound on its rounding error (Higham, Accuracy and Stability of
    // Numerical Algorithms, Alg. 5.1): |computed - exact| <= *errorBound for the stored
    // coefficients. A computed |p(t)| at or below the bound has no trustworthy sign.
    double eval(double t, double* errorBound) const {
        double y = c_[degree_];
        double mu = 0.5 * std::abs(y);
        const double at = std::abs(t);
        for (int i = degree_ - 1; i >= 0; --i) {
            y = std::fma(y, t, c_[i]);
            mu = std::fma(mu, at, std::abs(y));
        }
        // Step: 2 mu - |y| bounds the sum of the step errors in units of u = ulp / 2; the
        // gamma(1) factor covers the rounding of mu itself.
        *errorBound = (1.0 + tol::gamma(2 * degree_ + 2)) * tol::kUlp * 0.5 *
                      std::max(0.0, 2.0 * mu - std::abs(y));
        return y;
    }

    // p(t) and p'(t) together (one pass), for Newton steps.
    void evalWithDerivative(double t, double& value, double& slope) const {
        double y = c_[degree_], dy = 0.0;
        for (int i = degree_ - 1; i >= 0; --i) {
            dy = std::fma(dy, t, y);
            y = std::fma(y, t, c_[i]);
        }
        value = y;
        slope = dy;
    }

    // p'(t); the derivative of a constant is the constant 0.
    Polynomial derivative() const {
        if (degree_ == 0) return Polynomial{0.0};
        Polynomial d = ofDegree(degree_ - 1);
        for (int i = 1; i <= degree_; ++i) d.c_[i - 1] = i * c_[i];
        return d;
    }

    // q(t) = p(t + s): moves the origin to s (repeated synthetic division, n^2 / 2 fmas).
    // Used to solve near the roots, so that small roots of q are not drowned by large terms.
    Polynomial shifted(double s) const {
        Polynomial q = *this;
        for (int k = 0; k < degree_; ++k)
            for (int i = degree_ - 1; i >= k; --i) q.c_[i] = std::fma(q.c_[i + 1], s, q.c_[i]);
        return q;
    }

    // q(t) = p(k t): rescales the variable. Exact when k is a power of two (barring
    // over/underflow), which is how the solvers use it.
    Polynomial argumentScaled(double k) const {
        Polynomial q = *this;
        double f = 1.0;
        for (int i = 0; i <= degree_; ++i, f *= k) q.c_[i] *= f;
        return q;
    }

    // k p(t).
    Polynomial scaled(double k) const {
        Polynomial q = *this;
        for (int i = 0; i <= degree_; ++i) q.c_[i] *= k;
        return q;
    }

    // The largest coefficient magnitude (0 for the zero polynomial).
    double maxMagnitude() const {
        double m = 0.0;
        for (int i = 0; i <= degree_; ++i) m = std::max(m, std::abs(c_[i]));
        return m;
    }

private:
    std::array<double, kMaxDegree + 1> c_{};
    int degree_ = 0;
};

}  // namespace csg
