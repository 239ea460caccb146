#include "primitives/solvers/Trivariate.h"

#include <algorithm>
#include <cmath>

namespace csg {

namespace {

// q(s) = q(s) * (a + b s) + c: one Horner step on a polynomial in s (degree grows by one).
void hornerStep(Polynomial& q, int& deg, double a, double b, double c) {
    Polynomial r = Polynomial::ofDegree(deg + 1);
    r[deg + 1] = q[deg] * b;
    for (int i = deg; i >= 1; --i) r[i] = std::fma(q[i], a, q[i - 1] * b);
    r[0] = std::fma(q[0], a, c);
    q = r;
    ++deg;
}

// q(s) = q(s) * (a + b s) + c(s), c of degree cdeg <= deg + 1.
void hornerStepPoly(Polynomial& q, int& deg, double a, double b, const Polynomial& c, int cdeg) {
    hornerStep(q, deg, a, b, 0.0);
    for (int i = 0; i <= cdeg; ++i) q[i] += c[i];
}

// The same two steps on double-double polynomials (alongDD).
void hornerStepDD(PolynomialDD& q, int& deg, const DoubleDouble& a, double b,
                  const DoubleDouble& c) {
    PolynomialDD r;
    r.c[deg + 1] = q.c[deg] * DoubleDouble(b);
    for (int i = deg; i >= 1; --i) r.c[i] = q.c[i] * a + q.c[i - 1] * DoubleDouble(b);
    r.c[0] = q.c[0] * a + c;
    ++deg;
    r.degree = deg;
    q = r;
}

void hornerStepPolyDD(PolynomialDD& q, int& deg, const DoubleDouble& a, double b,
                      const PolynomialDD& c, int cdeg) {
    hornerStepDD(q, deg, a, b, 0.0);
    for (int i = 0; i <= cdeg; ++i) q.c[i] = q.c[i] + c.c[i];
}

}  // namespace

double Trivariate::maxMagnitude() const {
    double m = 0.0;
    for (int i = 0; i < termCount(); ++i) m = std::max(m, std::abs(c_[i]));
    return m;
}

double Trivariate::operator()(const Vec3& p) const {
    const int n = degree_;
    double fx = 0.0;
    for (int i = n; i >= 0; --i) {
        double fy = 0.0;
        for (int j = n - i; j >= 0; --j) {
            double fz = 0.0;
            for (int k = n - i - j; k >= 0; --k) fz = std::fma(fz, p.z, at(i, j, k));
            fy = std::fma(fy, p.y, fz);
        }
        fx = std::fma(fx, p.x, fy);
    }
    return fx;
}

Trivariate Trivariate::partial(int axis) const {
    Trivariate d(std::max(0, degree_ - 1));
    if (degree_ == 0) return d;
    for (int i = 0; i <= degree_; ++i)
        for (int j = 0; i + j <= degree_; ++j)
            for (int k = 0; i + j + k <= degree_; ++k) {
                const int e[3] = {i, j, k};
                if (e[axis] == 0) continue;
                int di = i, dj = j, dk = k;
                (axis == 0 ? di : axis == 1 ? dj : dk) -= 1;
                d.at(di, dj, dk) = e[axis] * at(i, j, k);
            }
    return d;
}

Polynomial Trivariate::along(const Vec3& p, const Vec3& u) const {
    const int n = degree_;
    // Step 1: outer Horner in X over blocks i = n .. 0; each block is a polynomial in (y, z).
    Polynomial fx;
    int degX = -1;
    for (int i = n; i >= 0; --i) {
        // Step 2: middle Horner in Y over rows j; each row is a polynomial in z alone.
        Polynomial fy;
        int degY = -1;
        for (int j = n - i; j >= 0; --j) {
            // Step 3: inner Horner in Z: the row's value along the line.
            Polynomial fz{at(i, j, n - i - j)};
            int degZ = 0;
            for (int k = n - i - j - 1; k >= 0; --k) hornerStep(fz, degZ, p.z, u.z, at(i, j, k));
            if (degY < 0)
                fy = fz, degY = degZ;
            else
                hornerStepPoly(fy, degY, p.y, u.y, fz, degZ);
        }
        if (degX < 0)
            fx = fy, degX = degY;
        else
            hornerStepPoly(fx, degX, p.x, u.x, fy, degY);
    }
    return fx;
}

PolynomialDD Trivariate::alongDD(const DoubleDouble p[3], const Vec3& u) const {
    const int n = degree_;
    // The steps of along(), every value a double-double.
    PolynomialDD fx;
    int degX = -1;
    for (int i = n; i >= 0; --i) {
        PolynomialDD fy;
        int degY = -1;
        for (int j = n - i; j >= 0; --j) {
            PolynomialDD fz;
            fz.c[0] = at(i, j, n - i - j);
            int degZ = 0;
            for (int k = n - i - j - 1; k >= 0; --k) hornerStepDD(fz, degZ, p[2], u.z, at(i, j, k));
            if (degY < 0)
                fy = fz, degY = degZ;
            else
                hornerStepPolyDD(fy, degY, p[1], u.y, fz, degZ);
        }
        if (degX < 0)
            fx = fy, degX = degY;
        else
            hornerStepPolyDD(fx, degX, p[0], u.x, fy, degY);
    }
    fx.degree = n;
    return fx;
}

}  // namespace csg
