// Quadratic error functions of dual contouring: the point that best fits a set of tangent
// planes (points p_i with unit normals n_i), minimizing sum (n_i . (x - p_i))^2.
#pragma once

#include "primitives/base/Bounds.h"
#include "primitives/base/Math.h"

namespace csg {

// Accumulates planes in 3-D and solves for the feature point of a cell.
class Qef3 {
public:
    void add(const Vec3& p, const Vec3& n);
    int count() const { return count_; }
    // The mean of the added points (the fallback when the planes are inconsistent).
    Vec3 massPoint() const { return count_ ? sum_ / double(count_) : Vec3(0.0); }
    // Minimizer relative to the mass point, with directions of small curvature (eigenvalues
    // below tol::kQefEigenRel of the largest) left at the mass point: a flat patch gives a point
    // on the plane, a crease a point on its line, a corner the corner. When the minimizer falls
    // outside cell, it is clamped to the cell, and the clamped point or the mass point (which
    // lies inside), whichever fits the planes better, is returned.
    Vec3 solve(const Bounds3& cell) const;
    // sum (n_i . (x - p_i))^2: how badly x fits the planes.
    double error(const Vec3& x) const {
        return glm::dot(x, ata_ * x) - 2.0 * glm::dot(atb_, x) + btb_;
    }

private:
    Mat3 ata_{0.0};
    Vec3 atb_{0.0};
    double btb_ = 0.0;
    Vec3 sum_{0.0};
    int count_ = 0;
};

// The 2-D case on a cell face: where the tangent lines of two crossings on the face meet.
// u and v are the face's in-plane axes. Returns false when the lines are nearly parallel (no
// crease on this face) or meet outside the face square [lo, hi] in (u, v).
bool creaseOnFace(const Vec3& p0, const Vec3& n0, const Vec3& p1, const Vec3& n1, int u, int v,
                  const Vec2& lo, const Vec2& hi, Vec3& crease);

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: m = R diag(w) R^T,
// with the eigenvectors as the columns of R.
void symmetricEigen(const Mat3& m, Vec3& w, Mat3& r);

}  // namespace csg
