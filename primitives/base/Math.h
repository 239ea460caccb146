// The one door to GLM: every file spells vectors and matrices through these aliases, so a
// precision study can swap the scalar type in one place.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace csg {

using Scalar = double;
using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;
using Vec4 = glm::dvec4;
using Mat3 = glm::dmat3;
using Mat4 = glm::dmat4;
using Affine = glm::dmat4x3;  // an affine map stored as 4 columns of 3 rows (no 0 0 0 1 row)

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.14159265358979323846;

// Point and direction transforms by an affine 4x4 matrix (the last row is 0 0 0 1).
inline Vec3 transformPoint(const Mat4& m, const Vec3& p) {
    return Vec3(m * Vec4(p, 1.0));
}
inline Vec3 transformVector(const Mat4& m, const Vec3& v) {
    return Mat3(m) * v;
}
// The same by an affine map stored as 3x4, in the operation order of the two above, so the
// results are the same bits, but without widening the matrix to 4x4 and 3x3 temporaries.
inline Vec3 transformPoint(const Affine& m, const Vec3& p) {
    return (m[0] * p.x + m[1] * p.y) + (m[2] * p.z + m[3]);
}
inline Vec3 transformVector(const Affine& m, const Vec3& v) {
    return m[0] * v.x + m[1] * v.y + m[2] * v.z;
}

// True when every entry of the matrix is a finite number.
inline bool isFinite(const Mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

}  // namespace csg
