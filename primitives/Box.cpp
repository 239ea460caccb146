// Notation: t is the parameter of the line o + t d; a slab is lo[a] <= p[a] <= hi[a] on one axis.
#include "primitives/Box.h"

#include <cassert>
#include <cmath>

namespace csg {

void Box::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    double tIn = -kInfinity, tOut = kInfinity;
    uint16_t faceIn = kClipFace, faceOut = kClipFace;
    for (int a = 0; a < 3; ++a) {
        // A line parallel to a slab is either inside it everywhere or nowhere; it must not
        // reach the division, where (lo - o) / 0 could give 0 * inf = NaN downstream.
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return;
            continue;
        }
        // Divide rather than multiply by 1 / d: one rounding instead of two.
        double tLo = (lo[a] - o[a]) / d[a];
        double tHi = (hi[a] - o[a]) / d[a];
        uint16_t faceLo = uint16_t(2 * a), faceHi = uint16_t(2 * a + 1);
        if (tLo > tHi) {
            std::swap(tLo, tHi);
            std::swap(faceLo, faceHi);
        }
        // Intersect with the slabs seen so far; on a tie the earlier axis keeps the end.
        if (tLo > tIn) tIn = tLo, faceIn = faceLo;
        if (tHi < tOut) tOut = tHi, faceOut = faceHi;
    }
    // d == 0 leaves both ends unconstrained (a point is no span); a d so tiny that t overflows
    // is the same degenerate line and must not leak infinity.
    if (faceIn == kClipFace || !std::isfinite(tIn) || !std::isfinite(tOut)) return;
    if (tIn > tOut) return;
    out.add(tIn, faceIn, tOut, faceOut);
}

bool Box::inside(const Vec3& p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
}

Vec3 Box::normal(const Vec3&, uint16_t face) const {
    assert(face < 6 && "Box has faces 0..5");
    Vec3 n(0.0);
    if (face >= 6) return Vec3(0.0, 0.0, 1.0);  // defined even for a bad face in release
    n[face / 2] = (face & 1) ? 1.0 : -1.0;
    return n;
}

}  // namespace csg
