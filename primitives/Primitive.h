// The primitive contract. A primitive is a plain value in its own local frame with its
// natural parameters. It knows nothing of trees or scenes; it answers four questions:
//   bounds()          local axis-aligned bounds (may be unbounded, never empty)
//   spans(o, d, out)  the spans of the whole line o + t d (t in (-inf, inf)) inside the
//                     solid, ascending; d is not unit length; o is already close to the
//                     primitive (the caller moves it to the entry of bounds()).
//                     A tangent touch may be reported as a zero-length span or omitted;
//                     the caller drops spans shorter than the coincidence tolerance.
//   inside(p)         point membership of the closed solid
//   normal(p, face)   outward unit normal at a point p on the given face; never NaN,
//                     with a defined direction at degenerate points (a cone's apex)
// and owns its identity, from which every table outside primitives/ is derived:
//   kName             the language's name for it ("cube"), used by probe, info, the
//                     command line's messages and the viewer's pick
//   describe(json)    its parameters as members of a JSON object (info's tree)
//
// Adding a primitive, the whole recipe:
//   1. primitives/NewShape.{h,cpp}: a struct meeting PrimitiveShape, with any of the optional
//      members below that apply; the .cpp on primitives/CMakeLists.txt.
//   2. One line: NewShape in the variant of primitives/Primitives.h.
//   3. Its language module in io/ (a row of io/BuiltinModules.cpp's table, or a module file
//      of its own such as io/SurfaceModule.cpp).
//   4. Its tests: tests/<shape>_test.cpp against an independent oracle, and a sample.
// Nothing in csg/ or viewer/ names a primitive: they dispatch over the variant.
#pragma once

#include <concepts>

#include "primitives/LocalSpans.h"
#include "primitives/base/Bounds.h"
#include "primitives/base/Json.h"
#include "primitives/base/Math.h"

namespace csg {

template <class P>
concept PrimitiveShape = requires(const P& p, const Vec3& v, LocalSpans& out, uint16_t face,
                                  JsonWriter& json) {
    { P::kName } -> std::convertible_to<const char*>;
    { p.describe(json) } -> std::same_as<void>;
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

// Optional: a primitive that lies inside a ball centred in its own frame says so. Placed by a
// similarity, the ball becomes a world-frame ball that rejects lines before any leaf frame is
// entered (csg/Compile.cpp); it pays only where it is much tighter than the box, as for a
// sphere. A primitive whose ball pays for some values only (a convex polyhedron) returns an
// infinite radius for the others, which compile takes as no ball.
struct LocalBall {
    Vec3 center{0.0};
    double radius = 0.0;
};
template <class P>
concept HasBoundingBall = requires(const P& p) {
    { p.boundingBall() } -> std::same_as<LocalBall>;
};

// Optional: a convex primitive says so (kConvex = true): a scene that is an intersection of
// convex solids cannot shadow itself, so the renderer casts no shadow rays for it.
template <class P>
concept HasConvexSolid = P::kConvex;

// Optional: a primitive whose whole surface is one plane (a half-space) says so, so that a
// client can compute per-leaf planar data once (the renderer's pattern frame).
template <class P>
concept HasPlanarSurface = P::kPlanar;

}  // namespace csg
