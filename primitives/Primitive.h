// The primitive contract. A primitive is a plain value in its own local frame with its
// natural parameters. It answers four questions and knows nothing of trees or scenes:
//   bounds()          local axis-aligned bounds (may be unbounded, never empty)
//   spans(o, d, out)  the spans of the whole line o + t d (t in (-inf, inf)) inside the
//                     solid, ascending; d is not unit length; o is already close to the
//                     primitive (the caller moves it to the entry of bounds()).
//                     A tangent touch may be reported as a zero-length span or omitted;
//                     the caller drops spans shorter than the coincidence tolerance.
//   inside(p)         point membership of the closed solid
//   normal(p, face)   outward unit normal at a point p on the given face; never NaN,
//                     with a defined direction at degenerate points (a cone's apex)
#pragma once

#include <concepts>

#include "primitives/LocalSpans.h"
#include "primitives/base/Bounds.h"
#include "primitives/base/Math.h"

namespace csg {

template <class P>
concept PrimitiveShape = requires(const P& p, const Vec3& v, LocalSpans& out, uint16_t face) {
    { p.bounds() } -> std::same_as<Bounds3>;
    { p.spans(v, v, out) } -> std::same_as<void>;
    { p.inside(v) } -> std::same_as<bool>;
    { p.normal(v, face) } -> std::same_as<Vec3>;
};

// Optional: a primitive may give tight world bounds under an affine map (a rotated sphere's
// box is smaller than its rotated local box). Without it, the local box corners are mapped.
template <class P>
concept HasTightBounds = requires(const P& p, const Mat4& m) {
    { p.boundsUnder(m) } -> std::same_as<Bounds3>;
};

// Optional: a primitive that may be a sheet (an open surface with no inside, e.g. a Bezier
// patch set with solid=false) says so. A sheet's spans() sets LocalSpans::sheet and lists each
// crossing as [t, t]; inside() is false; compile rejects it under difference/intersection.
template <class P>
concept HasSheet = requires(const P& p) {
    { p.isSheet() } -> std::same_as<bool>;
};

// Optional: a primitive whose parameters can be out of its domain (a negative radius, a
// spindle torus) says why, or returns nullptr when they are fine. compile() turns a reason
// into a CompileError at the node's source, so bad parameters never reach a ray.
template <class P>
concept HasValidation = requires(const P& p) {
    { p.invalidReason() } -> std::same_as<const char*>;
};

}  // namespace csg
