// Notation used throughout csg/ and primitives/:
//   t       ray parameter; the point is o + t d, the same t in world and local frames.
//   span    a closed interval [in.t, out.t] of t where the ray is inside a solid.
//   face    which surface of a leaf's primitive bounds a span end (primitive-defined);
//           kClipFace marks an end that is the ray's own tmin/tmax, not a surface.
//   flipped the solid lies on the other side of that surface (a difference's right
//           operand): the outward normal is the primitive's normal negated.
#pragma once

#include <cstdint>

#include "primitives/LocalSpans.h"

namespace csg {

// Which surface bounds a span end. Points and normals are not stored: they are computed
// on request from (leaf, face) by the scene, so shadow rays never pay for them.
struct Hit {
    double t = 0.0;
    uint32_t leaf = 0;
    uint16_t face = kClipFace;
    bool flipped = false;
    // The end of a zero-length span that is a crossing of a sheet: an open surface with no
    // inside (a bezier_patch with solid=false). Its span has in == out; merges keep it where
    // no solid covers it instead of dropping it as a sliver.
    bool sheet = false;

    bool isSurface() const { return face != kClipFace; }
};

struct Span {
    Hit in;
    Hit out;
};

}  // namespace csg
