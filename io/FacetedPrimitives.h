// The language side of faceting: the special variables a primitive call reads, with OpenSCAD's
// warnings, and the convex polyhedra that cylinder() and sphere() become when the curve mode
// (EvaluateOptions::curves) facets them. The geometry itself is io/Faceting.h's.
#pragma once

#include <optional>

#include "io/BoundArgs.h"
#include "io/Faceting.h"
#include "primitives/ConvexPolytope.h"

namespace io {

// The call's $fn, $fa and $fs: an argument of the call itself (the last one of a name), else
// the variable in scope (special variables are dynamically scoped). A value that is not a number
// reads as 0, as OpenSCAD's Value::toDouble does. $fa or $fs below kMinFragmentSetting (or not
// a number) is raised to it with a warning at the call, as OpenSCAD 2021 does for every
// primitive, whether or not it has curves.
FragmentSettings fragmentSettings(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx);
// The same read without clamping or warnings, as OpenSCAD's offset() and text() read them
// (they are no primitives to OpenSCAD and hand $fa and $fs to their fragment counts as they
// are).
FragmentSettings unclampedFragmentSettings(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx);

// A faceted solid as the convex polytope ray casts answer (origin: what describe() names).
csg::ConvexPolytope polytopeOf(FacetedSolid solid, csg::ConvexPolytope::Origin origin = {});

// The convex polyhedron OpenSCAD makes of cylinder(h, r1, r2, center), vertex for vertex, when
// the curve mode facets it (see CurveMode); nullopt when the exact cylinder stays. The
// parameters are valid (h > 0, radii >= 0 and not both 0). A count of fragments that would make
// more faces than a polyhedron may have (ConvexPolytope::kMaxPlanes) is an error at the call,
// found before anything is allocated.
std::optional<csg::ConvexPolytope> cylinderPolytope(Evaluator& e, const InstantiationStmt& s,
                                                    const FragmentSettings& settings, double h,
                                                    double r1, double r2, bool center);

// The same for sphere(r), r > 0.
std::optional<csg::ConvexPolytope> spherePolytope(Evaluator& e, const InstantiationStmt& s,
                                                  const FragmentSettings& settings, double r);

}  // namespace io
