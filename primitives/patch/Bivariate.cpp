#include "primitives/patch/Bivariate.h"

#include <algorithm>

namespace csg {

bool Bivariate::isZero() const {
    return leading().u < 0;
}

Monomial Bivariate::leading() const {
    for (int j = kMaxDegreeV; j >= 0; --j)
        for (int i = kMaxDegreeU; i >= 0; --i)
            if (c_[j][i] != 0.0) return {i, j};
    return {-1, -1};
}

int Bivariate::degreeU() const {
    int d = -1;
    for (int j = 0; j <= kMaxDegreeV; ++j)
        for (int i = kMaxDegreeU; i > d; --i)
            if (c_[j][i] != 0.0) {
                d = i;
                break;
            }
    return d;
}

double Bivariate::maxMagnitude() const {
    double m = 0.0;
    for (const auto& row : c_)
        for (double x : row) m = std::max(m, std::abs(x));
    return m;
}

void Bivariate::scale(double k) {
    for (auto& row : c_)
        for (double& x : row) x *= k;
}

bool Bivariate::subtractMultiple(double k, const Monomial& shift, const Bivariate& g) {
    if (g.degreeU() + shift.u > kMaxDegreeU || g.degreeV() + shift.v > kMaxDegreeV) return false;
    for (int j = 0; j + shift.v <= kMaxDegreeV; ++j)
        for (int i = 0; i + shift.u <= kMaxDegreeU; ++i)
            if (g.c_[j][i] != 0.0)
                c_[j + shift.v][i + shift.u] =
                    std::fma(-k, g.c_[j][i], c_[j + shift.v][i + shift.u]);
    return true;
}

void Bivariate::dropBelow(double threshold) {
    for (auto& row : c_)
        for (double& x : row)
            if (std::abs(x) <= threshold) x = 0.0;
}

std::array<double, Bivariate::kMaxDegreeV + 1> Bivariate::atU(double u) const {
    std::array<double, kMaxDegreeV + 1> r{};
    for (int j = 0; j <= kMaxDegreeV; ++j) {
        double y = 0.0;
        for (int i = kMaxDegreeU; i >= 0; --i) y = std::fma(y, u, c_[j][i]);
        r[j] = y;
    }
    return r;
}

double Bivariate::operator()(double u, double v) const {
    const auto r = atU(u);
    double y = 0.0;
    for (int j = kMaxDegreeV; j >= 0; --j) y = std::fma(y, v, r[j]);
    return y;
}

Vec2 Bivariate::gradient(double u, double v) const {
    std::array<double, kMaxDegreeV + 1> row{}, rowDu{};  // v^j coefficients and d/du at u
    for (int j = 0; j <= kMaxDegreeV; ++j)
        for (int i = kMaxDegreeU; i >= 0; --i) {
            rowDu[j] = std::fma(rowDu[j], u, row[j]);
            row[j] = std::fma(row[j], u, c_[j][i]);
        }
    double fu = 0.0, fv = 0.0;
    for (int j = kMaxDegreeV; j >= 0; --j) {
        fu = std::fma(fu, v, rowDu[j]);
        if (j > 0) fv = std::fma(fv, v, j * row[j]);
    }
    return {fu, fv};
}

double Bivariate::termMagnitude(double u, double v) const {
    const double au = std::abs(u), av = std::abs(v);
    double y = 0.0;
    for (int j = kMaxDegreeV; j >= 0; --j) {
        double row = 0.0;
        for (int i = kMaxDegreeU; i >= 0; --i) row = std::fma(row, au, std::abs(c_[j][i]));
        y = std::fma(y, av, row);
    }
    return y;
}

Bivariate Bivariate::planeDistance(const BezierPatch& patch, const Vec3& n, const Vec3& o) {
    // Cubic Bernstein to monomial: B_i(x) = sum_k M[i][k] x^k.
    static constexpr double M[4][4] = {{1, -3, 3, -1}, {0, 3, -6, 3}, {0, 0, 3, -3}, {0, 0, 0, 1}};
    double h[4][4];  // control heights n . (P_ij - o)
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) h[i][j] = dot(n, patch.at(i, j) - o);
    Bivariate f;
    for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l) {
            double s = 0.0;
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) s += M[i][k] * M[j][l] * h[i][j];
            f.c_[l][k] = s;
        }
    return f;
}

}  // namespace csg
