// OpenSCAD 2021.01's faceting of curves, the one place csgray states it (../shared/OPENSCAD.md
// §1): how many fragments a circle of radius r gets from $fn, $fa and $fs, and where the
// vertices of circle(), cylinder() and sphere() lie, to the bit. Pure functions of numbers:
// the 3-D modules build convex polytopes from them (io/FacetedPrimitives.h), the 2-D circle()
// takes circleVertices().
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "primitives/base/Math.h"

namespace io {

// What the curves of cylinder() and sphere() become (--curves; csgray's own torus and
// surfaces are exact in every mode):
//   Auto      faceted as OpenSCAD would where $fn decides the count ($fn > 0, or not finite);
//             exact where OpenSCAD's count would come from $fa and $fs;
//   Exact     every curve exact, $fn ignored;
//   OpenScad  everything faceted as OpenSCAD 2021 would, $fa and $fs included.
enum class CurveMode { Auto, Exact, OpenScad };

// "auto", "exact", "openscad".
const char* curveModeName(CurveMode mode);
// The mode of a name curveModeName gives; nullopt for anything else.
std::optional<CurveMode> parseCurveMode(std::string_view name);

// The special variables a primitive reads, after OpenSCAD's clamping of $fa and $fs
// (io/FacetedPrimitives.h reads them from a call). Defaults are OpenSCAD's.
struct FragmentSettings {
    double fn = 0.0;
    double fa = 12.0;  // degrees
    double fs = 2.0;   // length
};

// OpenSCAD's GRID_FINE (src/grid.h): a radius below it gets 3 fragments whatever the settings.
inline constexpr double kGridFine = 0x1p-20;
// OpenSCAD's F_MINIMUM (src/primitives.cc): $fa or $fs below it is raised to it, with a warning.
inline constexpr double kMinFragmentSetting = 0.01;

// OpenSCAD 2021's Calc::get_fragments_from_r: 3 when r < kGridFine or fn is not finite;
// trunc(fn) but at least 3 when fn > 0; else ceil(max(min(360 / fa, 2 pi r / fs), 5)). fa and fs
// are taken as given (clamping is the caller's, as in OpenSCAD). Where OpenSCAD's conversion to
// int would overflow (fn >= 2^31), the count saturates at INT32_MAX.
int64_t fragments(double r, double fn, double fa, double fs);
inline int64_t fragments(double r, const FragmentSettings& s) {
    return fragments(r, s.fn, s.fa, s.fs);
}

// Whether $fn decides the count (it is above 0, or not finite): fragments() then never reaches
// $fa and $fs.
bool fnDecidesCount(const FragmentSettings& settings);

// Whether a curve with these settings is faceted in this mode (see CurveMode).
bool isFaceted(CurveMode mode, const FragmentSettings& settings);

// OpenSCAD 2021's slices of a linear_extrude that twists or scales its axes unevenly, when the
// call gives no slices > 0 (GeometryEvaluator's extrudePolygon choosing among src/calc.cc's
// get_helix_slices, get_conical_helix_slices and get_diagonal_slices): rmaxSquared is the
// largest squared distance of a profile vertex from the origin, deltaSquared the largest
// squared distance a vertex v moves to diag(scale) v (read only without twist). 1 for an
// extrusion that neither twists nor scales unevenly. A count beyond INT32_MAX saturates there.
int64_t extrudeSlices(double rmaxSquared, double deltaSquared, double height, double twist,
                      csg::Vec2 scale, const FragmentSettings& settings);

// circle(r) with n fragments (OpenSCAD's generate_circle): vertex i = (r cos(360 i / n),
// r sin(360 i / n)), i = 0 .. n - 1, the first on +x, counter-clockwise, inscribed.
std::vector<csg::Vec2> circleVertices(double r, int64_t n);

// The rings of sphere(r) with n fragments: (n + 1) / 2, at polar angles 180 (i + 1/2) / rings.
inline int64_t sphereRingCount(int64_t n) {
    return (n + 1) / 2;
}

// Faces of the faceted solids, computed before any vertex is made so that a caller can refuse a
// count no solid may have (sphere(1, $fn = 1e7) has 5e13) without allocating anything.
// cylinder: n sides, plus a cap at each end whose radius is not 0.
uint64_t facetedCylinderFaceCount(int64_t n, double r1, double r2);
// sphere: n (rings - 1) sides between rings, plus the two flat caps.
uint64_t facetedSphereFaceCount(int64_t n);

// A closed convex polyhedron as vertices and faces: face f has the vertices
// faceVertices[faceStarts[f] .. faceStarts[f + 1]) (counter-clockwise seen from outside).
struct FacetedSolid {
    std::vector<csg::Vec3> vertices;
    std::vector<uint32_t> faceVertices;
    std::vector<uint32_t> faceStarts{0};  // one more entry than there are faces
};

// cylinder(h, r1, r2) with n fragments, from z1 to z2 (0 and h, or -h/2 and h/2 centred):
// the ring of circleVertices(r1, n) at z1 and of circleVertices(r2, n) at z2, at the same
// angles; a zero radius is one apex vertex on the axis. Faces: side i (between vertices i and
// i + 1 of the rings) for i = 0 .. n - 1, then the cap at z1, then the cap at z2 (only for a
// radius above 0). Vertices: the z1 ring (or apex), then the z2 ring (or apex).
FacetedSolid facetedCylinder(double r1, double r2, double z1, double z2, int64_t n);

// sphere(r) with n fragments: ring i (0 at the top) at polar angle phi_i = 180 (i + 1/2) / rings
// is circleVertices(r sin(phi_i), n) at z = r cos(phi_i); no pole vertices. Vertices: ring by
// ring, vertex k of ring i at i n + k. Faces: the trapezoid between rings i and i + 1 at
// azimuths k and k + 1 as face i n + k, then the top cap (ring 0), then the bottom cap.
FacetedSolid facetedSphere(double r, int64_t n);

}  // namespace io
