#include "primitives/patch/Resultant.h"

namespace csg {

int intersectByResultant(const BezierPatch&, const Vec3&, const Vec3&, PatchCrossings&,
                         ResultantStats* stats) {
    if (stats) *stats = ResultantStats{};
    return 0;  // placeholder until the resultant lands
}

int intersectByResultant(const BezierPatch& patch, const Vec3& o, const Vec3& d,
                        PatchCrossings& out) {
    return intersectByResultant(patch, o, d, out, nullptr);
}

}  // namespace csg
