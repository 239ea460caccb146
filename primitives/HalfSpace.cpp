// Notation: t is the parameter of the line o + t d; the solid is dot(n, p) <= offset with
// n = planeNormal (any length). Its spans have one end at +-infinity with face kClipFace.
#include "primitives/HalfSpace.h"

#include <cmath>

namespace csg {

Bounds3 HalfSpace::bounds() const {
    const Vec3& n = planeNormal;
    // Only an axis-aligned normal bounds one coordinate; any tilt lets every coordinate
    // run to infinity on the solid side.
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        if (n[a] == 0.0 || n[b] != 0.0 || n[c] != 0.0) continue;
        Bounds3 box = Bounds3::everything();
        const double limit = offset / n[a];
        if (!std::isfinite(limit)) return box;  // a subnormal normal: no usable bound
        if (n[a] > 0.0)
            box.hi[a] = limit;
        else
            box.lo[a] = limit;
        return box;
    }
    return Bounds3::everything();
}

void HalfSpace::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    const double nd = glm::dot(planeNormal, d);
    const double t = (offset - glm::dot(planeNormal, o)) / nd;
    // Parallel to the plane (or so nearly that the crossing overflows): all or nothing.
    if (nd == 0.0 || !std::isfinite(t)) {
        if (inside(o)) out.add(-kInfinity, kClipFace, kInfinity, kClipFace);
        return;
    }
    // Moving along d raises dot(n, p) when nd > 0, so the solid is the part before the plane.
    if (nd > 0.0)
        out.add(-kInfinity, kClipFace, t, 0);
    else
        out.add(t, 0, kInfinity, kClipFace);
}

Vec3 HalfSpace::normal(const Vec3&, uint16_t) const {
    const double len = glm::length(planeNormal);
    // A zero normal (everything or nothing) has no plane to be on; return a defined value.
    return len > 0.0 && std::isfinite(len) ? planeNormal / len : Vec3(0.0, 0.0, 1.0);
}

}  // namespace csg
