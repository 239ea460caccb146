#include "primitives/base/Bounds.h"

namespace csg {

Bounds3 transformBounds(const Mat4& m, const Bounds3& b) {
    if (b.empty()) return b;
    if (!b.finite()) return Bounds3::everything();
    Bounds3 out;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p(corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y,
                     corner & 4 ? b.hi.z : b.lo.z);
        out.extend(transformPoint(m, p));
    }
    return out;
}

}  // namespace csg
