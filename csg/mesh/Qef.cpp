#include "csg/mesh/Qef.h"

#include <cmath>

#include "primitives/base/Tolerances.h"

namespace csg {

void symmetricEigen(const Mat3& m, Vec3& w, Mat3& r) {
    // GLM is column-major: a[col][row]; the matrix is symmetric so either reading works.
    Mat3 a = m;
    r = Mat3(1.0);
    for (int sweep = 0; sweep < 32; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (off <= tol::kJacobiOffDiagonalRel * diag || off == 0.0) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (a[p][q] == 0.0) continue;
                // Rotation that zeroes a[p][q] (Numerical Recipes' stable form).
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t =
                    std::copysign(1.0, theta) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
                const double cs = 1.0 / std::sqrt(t * t + 1.0), sn = t * cs;
                Mat3 g(1.0);
                g[p][p] = cs;
                g[q][q] = cs;
                g[q][p] = sn;  // column q, row p
                g[p][q] = -sn;
                a = glm::transpose(g) * a * g;
                r = r * g;
            }
        }
    }
    w = Vec3(a[0][0], a[1][1], a[2][2]);
}

void Qef3::add(const Vec3& p, const Vec3& n) {
    ata_ += glm::outerProduct(n, n);
    const double d = glm::dot(n, p);
    atb_ += n * d;
    btb_ += d * d;
    sum_ += p;
    ++count_;
}

Vec3 Qef3::solve(const Bounds3& cell) const {
    const Vec3 mass = massPoint();
    if (count_ == 0) return cell.center();

    // Step 1: eigen-decompose A^T A (eigenvalues are squared singular values of A).
    Vec3 w;
    Mat3 r;
    symmetricEigen(ata_, w, r);
    const double wMax = std::max({std::fabs(w.x), std::fabs(w.y), std::fabs(w.z)});

    // Step 2: pseudo-inverse applied to the residual at the mass point, dropping directions
    // whose curvature is too small to locate a feature along them.
    const Vec3 rhs = atb_ - ata_ * mass;
    Vec3 x = mass;
    for (int i = 0; i < 3; ++i) {
        if (w[i] <= tol::kQefEigenRel * wMax) continue;
        const Vec3 e = r[i];
        x += e * (glm::dot(e, rhs) / w[i]);
    }

    // Step 3: a minimizer just outside the cell is a crease passing near the cell's side:
    // clamping keeps it on the crease. One far outside means the planes disagree (two
    // features, a curved patch seen at a grazing angle): the mass point fits better then.
    if (cell.contains(x)) return x;
    const Vec3 clamped = glm::clamp(x, cell.lo, cell.hi);
    return error(clamped) < error(mass) ? clamped : mass;
}

bool creaseOnFace(const Vec3& p0, const Vec3& n0, const Vec3& p1, const Vec3& n1, int u, int v,
                  const Vec2& lo, const Vec2& hi, Vec3& crease) {
    // Step 1: the tangent lines in the face plane, m_i . (y - q_i) = 0 with in-plane normals.
    const Vec2 q0(p0[u], p0[v]), q1(p1[u], p1[v]);
    Vec2 m0(n0[u], n0[v]), m1(n1[u], n1[v]);
    const double l0 = glm::length(m0), l1 = glm::length(m1);
    if (l0 == 0.0 || l1 == 0.0) return false;
    m0 /= l0;
    m1 /= l1;

    // Step 2: nearly parallel lines meet far away or nowhere: no crease on this face.
    const double det = m0.x * m1.y - m0.y * m1.x;
    if (std::fabs(det) < std::sin(tol::kCreaseAngle)) return false;

    // Step 3: Cramer's rule for the meeting point, kept only inside the face square.
    const double r0 = glm::dot(m0, q0), r1 = glm::dot(m1, q1);
    const Vec2 y((r0 * m1.y - r1 * m0.y) / det, (m0.x * r1 - m1.x * r0) / det);
    if (y.x < lo.x || y.x > hi.x || y.y < lo.y || y.y > hi.y) return false;
    crease = p0;  // the face's own coordinate (equal for both points)
    crease[u] = y.x;
    crease[v] = y.y;
    return true;
}

}  // namespace csg
