#include "primitives/solvers/Trivariate.h"

#include <algorithm>
#include <cmath>

#include "primitives/solvers/ErrorFree.h"

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

// The same two steps on double-double polynomials (alongDD), in place and on storage that is
// not zeroed first (each coefficient is written before it is read): a row's copy and zeroing
// cost more than its arithmetic at low degree.
struct RawDD {
    double hi, lo;
};
struct DDRow {
    RawDD c[Trivariate::kMaxDegree + 1];
    int deg;
};
DoubleDouble dd(const RawDD& v) {
    return {v.hi, v.lo};
}
RawDD raw(const DoubleDouble& v) {
    return {v.hi, v.lo};
}
// a * b for a double-double a and a double b.
DoubleDouble timesDouble(const DoubleDouble& a, double b) {
    const Sum2 p = twoProduct(a.hi, b);
    return quickSum(p.hi, p.lo + a.lo * b);
}

// q(s) = q(s) * (a + b s) + c.
void hornerStepDD(DDRow& q, const DoubleDouble& a, double b, const DoubleDouble& c) {
    q.c[q.deg + 1] = raw(timesDouble(dd(q.c[q.deg]), b));
    for (int i = q.deg; i >= 1; --i) q.c[i] = raw(dd(q.c[i]) * a + timesDouble(dd(q.c[i - 1]), b));
    q.c[0] = raw(dd(q.c[0]) * a + c);
    ++q.deg;
}

// q(s) = q(s) * (a + b s) + c(s), c of degree <= q's + 1.
void hornerStepPolyDD(DDRow& q, const DoubleDouble& a, double b, const DDRow& c) {
    hornerStepDD(q, a, b, 0.0);
    for (int i = 0; i <= c.deg; ++i) q.c[i] = raw(dd(q.c[i]) + dd(c.c[i]));
}

void assign(DDRow& to, const DDRow& from) {
    to.deg = from.deg;
    for (int i = 0; i <= from.deg; ++i) to.c[i] = from.c[i];
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
    DDRow fx, fy, fz;
    fx.deg = -1;
    for (int i = n; i >= 0; --i) {
        fy.deg = -1;
        for (int j = n - i; j >= 0; --j) {
            fz.deg = 0;
            fz.c[0] = {at(i, j, n - i - j), 0.0};
            for (int k = n - i - j - 1; k >= 0; --k) hornerStepDD(fz, p[2], u.z, at(i, j, k));
            if (fy.deg < 0)
                assign(fy, fz);
            else
                hornerStepPolyDD(fy, p[1], u.y, fz);
        }
        if (fx.deg < 0)
            assign(fx, fy);
        else
            hornerStepPolyDD(fx, p[0], u.x, fy);
    }
    PolynomialDD out;
    out.degree = n;
    for (int i = 0; i <= fx.deg; ++i) out.c[i] = dd(fx.c[i]);
    return out;
}

}  // namespace csg
