#include "primitives/patch/Intersect.h"

#include "primitives/patch/Clip.h"
#include "primitives/patch/Groebner.h"
#include "primitives/patch/GroebnerCertified.h"
#include "primitives/patch/GroebnerExact.h"
#include "primitives/patch/NewtonSubdivision.h"
#include "primitives/patch/Resultant.h"

namespace csg {

int intersectPatch(PatchMethod method, const BezierPatch& patch, const Vec3& o, const Vec3& d,
                   PatchCrossings& out) {
    switch (method) {
        case PatchMethod::Groebner:
            return intersectByCertifiedGroebner(patch, o, d, out);
        case PatchMethod::Resultant:
            return intersectByResultant(patch, o, d, out);
        case PatchMethod::Clip:
            return intersectByClip(patch, o, d, out);
        case PatchMethod::Newton:
            return intersectByNewton(patch, o, d, out);
        case PatchMethod::GroebnerExact:
            return intersectByExactGroebner(patch, o, d, out);
        case PatchMethod::GroebnerFloat:
            return intersectByGroebner(patch, o, d, out);
    }
    return 0;
}

const char* patchMethodName(PatchMethod method) {
    switch (method) {
        case PatchMethod::Groebner:
            return "groebner";
        case PatchMethod::Resultant:
            return "resultant";
        case PatchMethod::Clip:
            return "clip";
        case PatchMethod::Newton:
            return "newton";
        case PatchMethod::GroebnerExact:
            return "groebner-exact";
        case PatchMethod::GroebnerFloat:
            return "groebner-float";
    }
    return "?";
}

}  // namespace csg
