#include "primitives/patch/Groebner.h"

namespace csg {

int intersectByGroebner(const BezierPatch&, const Vec3&, const Vec3&, PatchCrossings&,
                        GroebnerStats* stats) {
    if (stats) *stats = GroebnerStats{};
    return 0;  // placeholder until the reduction lands
}

int intersectByGroebner(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                        PatchCrossings& out) {
    return intersectByGroebner(patch, o, d, out, nullptr);
}

}  // namespace csg
