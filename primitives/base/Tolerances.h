// Every tolerance csgray uses, each with its unit and the reason for its value.
// A tolerance that is not here does not exist: code refers to these names only.
#pragma once

#include <limits>

namespace csg::tol {

// Machine epsilon of double: the relative rounding error of one operation is at most
// kUlp / 2.
inline constexpr double kUlp = std::numeric_limits<double>::epsilon();

// pbrt's gamma(n): a bound on the relative error accumulated by n floating-point
// operations, each rounding by at most kUlp / 2.
constexpr double gamma(int n) {
    return (n * kUlp / 2) / (1 - n * kUlp / 2);
}

// Span ends closer than this are one boundary (unit: ray parameter t, relative).
// Two ends a and b coincide when |a - b| <= kCoincidentRel * (originScale + max(|a|, |b|)),
// where originScale = |o| / |d| of the world ray. Why this form: the point o + t d carries an
// absolute error of about ulp(|o| + |t| |d|), i.e. ulp(originScale + |t|) in units of t, and
// one primitive solve adds a few hundred ulps at most. 1e-9 leaves a margin of ~10^4 over
// that, yet is ~10^6 below the smallest feature (1e-3 of the part size) a test or sample
// resolves at any scale. The same rule drops spans shorter than this (slivers from
// coincident faces, tangent rays) and fuses spans separated by less (face-sharing parts).
inline constexpr double kCoincidentRel = 1e-9;

// A difference A - B keeps a span without B being solved when a piece of A's spans longer
// than this many coincidence slacks lies outside every box that bounds one of B's operands
// along the ray, each box widened by one slack (unit: the slack of kCoincidentRel at the ends
// of A's hull, the largest any end of that merge gets). Why 2: B's span ends lie inside their
// boxes up to one solve's error (a few hundred ulps, far below a slack), so B misses the piece
// but for its widened ends, and the piece is then longer than the one slack below which the
// merge would drop it: the regularized A - B is not empty, and its first span starts where
// A's does when the piece does (csg/Query.cpp, Evaluator::uncovered).
inline constexpr double kUncoveredPieceSlacks = 2.0;

// closest() answers a ray that starts inside a top-level object with that object's exit when
// no other object has solid within this many coincidence slacks of it (csg/Query.cpp,
// exitAlone; unit: the slack at the exit). Why 4: the union closes a gap of up to one slack
// after the exit (a slack taken at the gap's far end, larger by a relative 1e-9 at most), and
// an object's span there that the window clips to less than a slack would be dropped as a
// sliver by any(); with four, a span beginning within a slack of the exit keeps three inside
// the window. Half a slack let closest() differ from the whole list (query_test).
inline constexpr double kExitWindowSlacks = 4.0;

// A ray is taken to miss a node's bounding ball (csg/Compiled.h, BoundingBall) only when the
// line passes farther than radius + this fraction of (|ray origin| + |ball centre| + radius)
// from the centre (unit: relative). Why: the line's distance is computed with an absolute
// error of a few ulps of |o| + |c|; the sphere's own solve, in its local frame, errs by a
// few hundred ulps of the same magnitudes (the frame map and the quadratic, whose tangent
// rays it may still report as short spans). 1e-9 is the coincidence rule's margin
// (kCoincidentRel) over both, so a ray the ball rejects is one the sphere never reports.
inline constexpr double kBallMarginRel = 1e-9;

// A sphere leaf gets a bounding ball only when its transform is a similarity: the columns of
// the linear part have one length and are orthogonal, to this fraction of that length
// (unit: relative). Why: the ball's radius is the sphere's times the longest column, which
// bounds the ellipsoid to within this fraction, 1000x inside kBallMarginRel; rotations built
// from rounded sines and cosines are orthogonal to a few ulps, far within it.
inline constexpr double kSimilarityRel = 1e-12;

// A ray-box slab test widens both ends by this fraction of their magnitude so that rounding
// in the test never culls a box the exact test would hit (pbrt's 2 gamma(3)).
inline constexpr double kSlabWiden = 2 * gamma(3);

// A grid cell (primitives/base/Grid.h) lists every child whose box, widened by this fraction of the
// grid's size (the largest coordinate magnitude or side of its box), overlaps the cell (unit:
// relative). Why: the walk finds the cells along a ray from o + t d and from cell faces
// computed as lo + i * size, each rounded to a few ulps of the grid's size; an object within
// that of a cell the walk did not enter would be missed where the slab test (kSlabWiden) and
// the SAH walk still meet it. 1e-9 leaves ~10^6 over those roundings for rays from as far as
// 10^3 grid sizes away, and is far below a cell's side, so a child gains a neighbouring
// cell only when it touches it.
inline constexpr double kGridMarginRel = 1e-9;

// A transform whose linear part has |det| below this fraction of the cube of its largest
// column length is singular for our purposes (unit: relative). Inverting it would amplify
// rounding by more than 1e12, so localFromWorld would be garbage: compile rejects it, and so
// does multmatrix() when the part is read (io/BuiltinModules.cpp), where the error can point
// at the matrix.
inline constexpr double kSingularDetRel = 1e-12;

// A range [begin : step : end] of the language has floor((end - begin) / step + this) + 1
// elements (unit: steps; io/Value.cpp, Range::count). Why: a decimal step is not a double, so
// the quotient of [0 : 0.1 : 0.3] comes out a few ulps below 3 and would drop the last
// element OpenSCAD gives. A few ulps of the count is ~1e-10 up to a million elements, far
// below 1e-9; no range written on purpose ends within 1e-9 of a step short of an element.
inline constexpr double kRangeStepSlack = 1e-9;

// A polynomial value within this many times its running rounding-error bound (Horner,
// Polynomial::eval) is zero for the root solvers (unit: multiples of the bound). Such a value
// has no trustworthy sign, so a local extremum there is a tangency (double root) and two roots
// with such a value between them are one cluster. Why 8: the bound covers evaluation only;
// coefficients computed from a ray (the torus quartic) carry a few ulps of their own, which
// costs at most a few more bounds' worth.
inline constexpr double kRootResidualFactor = 8.0;

// Two candidate roots stay two when p at their midpoint exceeds this many times its rounding
// bound (unit: multiples of the bound; solvers/Roots.h, hasProvableSign). Why 1: the bound is
// rigorous, so beyond it the computed sign is the exact sign of the polynomial as stored, and
// double precision has resolved the pair. kRootResidualFactor's margin for coefficients that
// carry errors of their own is not applied here: it merged resolvable decimal clusters (four
// roots 1e-3 apart near 3, |p| ~4 bounds between them) into one tangency. A caller whose
// coefficients are computed (a ray's chord polynomial) judges its thin spans against that
// error itself (AlgebraicSurface::spans).
inline constexpr double kRootSeparationFactor = 1.0;

// Fujiwara's root bound (solvers/Roots.h) is widened by this fraction (unit: relative). The
// bound is attained (p = t - 5 has its root on it) and is computed with log2/exp2, a few ulps
// off; 1e-9 covers that by 10^6 and only enlarges a range that holds no roots anyway.
inline constexpr double kRootBoundMargin = 1e-9;

// The subdivision solvers (Descartes, Bernstein, interval) split an interval at most this
// many times in a row (unit: halvings). 2^-80 of the range is below double resolution of any
// root at least 2^-27 of the range from 0; deeper clusters are decided by clusterRoots().
inline constexpr int kMaxSubdivisionDepth = 80;

// The 50-digit reference root finder (solvers/reference/RootReference.h) stops when its Newton
// step or its bracket is at most this fraction of 1 + |t| (unit: relative). Why: 1e-45 is five
// digits above the 50-digit working precision, so the loop ends instead of chasing rounding,
// and still ~30 digits below double's, so the reference is exact for measuring double errors.
inline constexpr double kReferenceRootStepRel = 1e-45;

// The computed hit point o + t d of a closest() answer is within gamma(kHitPointErrorOps) *
// (|o| + |t d|) of the true surface point, per component (unit: operation counts of gamma).
// Why 1024: forming the point costs 3 roundings, but t itself carries the primitive solve's
// error, "a few hundred ulps" of |o| / |d| + |t| (see kCoincidentRel), which becomes a point
// error of the same relative size. 1024 covers that with margin and is still ~1e-13 of the
// distance to the eye: a secondary ray's origin offset by this bound along the normal never
// re-hits the surface it leaves, yet moves by far less than a pixel at any scale.
inline constexpr int kHitPointErrorOps = 1024;

// The torus solves its quartic over the line's range inside the bounding slab and cylinder,
// widened by this fraction of R + r (unit: relative to the torus size). The torus touches
// both bounds, and a root there is found only to ~1e-13 of the size (1e-11 for r/R = 1e-3)
// before polishing, so without the margin a grazing root would fall out of range; 1e-6 keeps
// a 1e5 safety factor and costs nothing, as F > 0 everywhere outside the torus.
inline constexpr double kTorusRangeMargin = 1e-6;

// The torus's Newton iterations on its tube form G (primitives/Torus.cpp: the crossings, and
// the critical points that cut the line into monotone pieces) stop after a step of at most this
// fraction of the minor radius r (unit: relative to r). Why: convergence is quadratic, a step
// of h leaving an error of about h^2 G'' / (2 |G'|), while rounding alone limits a crossing to
// ~ulp (R + r)^2 / |G'| (G is evaluated to that); with G'' <= 2 the first stays below the
// second for h below ~1e-8 (R + r), and 1e-9 r is below that for every torus. A critical point
// needs less (G is flat there) but shares the rule. Smaller only adds an evaluation per root.
inline constexpr double kTubeNewtonStep = 1e-9;
// A tube-form crossing where the line meets the tube within this cosine of tangent (|G'| below
// 2 r kTubeGrazingCos) gets one Newton step on G computed in double-double (Torus.cpp,
// accurateG). G in double is off by ~ulp(|p|) r (the point b + s u and rho are rounded), which
// moves a crossing by that over |G'| = 2 r cos: a few ulps at most angles, but up to ~12 ulps
// of t at the grazing crossings of torus_test's lines (cos ~ 0.01). At 1/8, ~2% of the
// crossings of random lines are polished and every test line's ends come within ~1.5 ulps
// (1/4 gains a fraction of an ulp for three times the polishing).
inline constexpr double kTubeGrazingCos = 0.125;

// The torus answers a line that leaves it for good without solving (Torus.cpp, leavesForGood)
// only where G is convex at the start by this margin: G'' = 2 (1 - R c^2 / rho^3) >
// 2 kTubeConvexRel, i.e. rho^3 beyond the concave piece's reach R c^2 by this fraction (unit:
// relative). Why: rho^3 and the quotient are rounded by a few ulps, and at G'' = 0 rounding
// could hide a concave stretch ahead. 1e-6 is ten orders above that rounding and gives up only
// lines that start within ~3e-7 of the concave piece's end, which the full solve then takes.
inline constexpr double kTubeConvexRel = 1e-6;

// Root polishing (primitives/solvers/Polish.h). Polisher::Auto polishes a double root in
// double-double when its estimated error (the evaluation's rounding bound, plus for a surface
// its chord coefficients' rounding bound and for a torus its tube form's, over |p'|) exceeds
// this many ulps of t (unit: ulps of the root). Why 1/2: a root within half an ulp of the exact
// one is within one ulp after its own final rounding, the accuracy the polish promises; the
// estimate is an upper bound, so a root left alone is never worse than that.
inline constexpr double kPolishConditionUlps = 0.5;
// A polisher stops once a step is at most this fraction of the root (unit: relative). Why
// 2^-104: double-double carries ~106 bits, so a smaller step is rounding noise of the
// residual; the rounding to double that follows needs ~2^-60 at most.
inline constexpr double kPolishStepRel = 0x1p-104;
// ... or after this many steps (unit: iterations). Why 16: from a double root (>= 1 correct
// bit for the ill-conditioned roots this is for) quadratic convergence reaches 2^-104 in ~7
// steps; Newton's linear convergence on a root listed once but nearly double needs more, and
// the result is then no worse than its start (a step that does not lower |p| is not taken).
inline constexpr int kPolishMaxSteps = 16;

// Mesh export (csg/mesh/). The QEF of a cell drops eigen-directions of A^T A whose eigenvalue
// is below this fraction of the largest (unit: relative). Eigenvalues are squared singular
// values, so this is DC's usual 0.1 singular-value cut: planes within ~6 degrees of each other
// do not locate a feature along their common direction (a smooth patch gives the mass point,
// not a far-off intersection of nearly parallel tangent planes).
inline constexpr double kQefEigenRel = 1e-2;

// The QEF's Jacobi eigen-decomposition (csg/mesh/Qef.cpp, symmetricEigen) stops when the sum of
// squares off the diagonal is at most this fraction of the sum of squares on it (unit:
// relative, of squares). Why: that is off-diagonal entries ~1e-15 of the diagonal's, a few
// ulps: a further rotation would only turn rounding, and the eigenvalues it leaves err by far
// less than the kQefEigenRel cut can notice.
inline constexpr double kJacobiOffDiagonalRel = 1e-30;

// Two tangent lines on a cell face that meet at less than this angle (unit: radians, 20 deg)
// are one smooth curve: no crease vertex on the face. A crease of a part (box edge, a cut's
// rim) meets at far more; a smooth surface sampled finely enough to meet a tolerance turns by
// much less across one cell.
inline constexpr double kCreaseAngle = 0.349;

// The first meshing pass assumes the part's smallest curvature radius is this fraction of its
// bounds' diagonal (unit: relative). Only the starting grid depends on it: later passes
// measure the error and refine, so a wrong guess costs a pass, not accuracy.
inline constexpr double kMeshReferenceRadius = 0.05;

// The adaptive octree of dual contouring (csg/mesh/DualContour.h) merges a block of cells into
// one vertex only when that vertex lies within this fraction of the tolerance of every tangent
// plane sampled in the block (unit: relative to T). A merged block's triangles run from its
// vertex to crossings on its edges and to its neighbours' vertices, spanning up to twice the
// block, so their sagitta over a curved patch is up to ~4x the per-block plane distance on
// a sphere; a quarter keeps that within T where the grid's own error is small (smooth
// patches: the grid's worst errors sit at creases, which never merge), and the
// measure-and-refine loop still measures the result.
inline constexpr double kOctreeFlatFraction = 0.25;

// ... and only when every sampled normal in the block lies within this angle of their mean
// (unit: radians, 8 degrees). Two normals of a block then differ by at most 16 degrees, below
// kCreaseAngle's 20: no face of a merged block carries a crease vertex, and a crease (a box
// edge, a rim) never merges.
inline constexpr double kOctreeConeAngle = 0.1396;

// A fan triangle of dual contouring at a merged octree block's vertex, where the crossing lies
// on the block's own smooth patch, must face within this of the exact normal at the crossing
// (unit: cosine, 30 degrees); else the ring is fanned from another of its vertices, or the block
// is split up again. A merged block's triangles lie within its narrow normal cone
// (kOctreeConeAngle) plus the curvature over its neighbours; one turned further is a fold (the
// block's vertex sits where the surface does not cross the face it shares with a neighbour) or
// a crease that the export's shading would split (kShadingCreaseDegrees) on a smooth surface.
inline constexpr double kOctreeFanTurnCos = 0.866;

// The exact boundary of an all-polyhedral part (csg/mesh/PolyhedralBoundary.h). A vertex within
// this fraction of the part's size (max(1, diagonal, largest |coordinate|)) of a cutting plane
// lies on it (unit: relative). Why: the planes and the cut points come from a few products and
// one division of world coordinates, ~10^2 ulps of the size, 10^4 below this; and no part puts
// features 10^-10 of its size apart on purpose.
inline constexpr double kPolyBoundaryOnPlaneRel = 1e-10;
// ... positions closer than this fraction of the size are one vertex, a vertex this close to
// another piece's edge is put into it, a triangle's corner this close to the line through the
// other two is on it (no ear), and the pieces of one face are merged by collapses that
// move no vertex farther than this off the face's plane (unit: relative). Why: ten times the
// on-plane slack, so the same corner reached through different cuts (each within it of the
// exact point) always welds.
inline constexpr double kPolyBoundaryWeldRel = 1e-9;
// Two faces whose unit normals' dot product is within this of +-1 are parallel: a coplanar one
// cuts along its edges, a parallel one elsewhere not at all (unit: 1 - |cos|). Why: 1e-12 is an
// angle of 1.4e-6 rad; the line where faces that close to parallel meet is ill-conditioned,
// while OpenSCAD's coplanar faces (a cube on a cube) have equal normals to a few ulps.
inline constexpr double kPolyBoundaryParallelCos = 1e-12;
// Sheets of solids that touch along an edge are told apart only where every wedge between
// neighbouring triangles around the edge is wider than this (csg/mesh/TouchingSheets.h; unit:
// radians). Why: the wedges of a contact are angles between faces of different solids, far
// above the ~1e-15 rad that rounding gives; a narrower one is a face folded onto another (a
// face written twice, a fin of no volume), a defect checkTopology must go on reporting.
inline constexpr double kTouchingSheetsMinWedge = 1e-9;
// A piece is classified on the stretch of its line within this many on-plane distances
// (kPolyBoundaryOnPlaneRel) of the piece (unit: multiples of that distance). Why: the span end
// on the piece's own face is at t = 0 to rounding (~1e-16 of the size), far inside 1e-7 of the
// size, while a stretch that short is missed by the bounds of every leaf not within it.
inline constexpr double kPolyBoundaryClassifyReach = 1e3;

// minkowski() with an exact ball (csg/derived/Minkowski3D.h) puts no cylinder along an edge whose
// two triangles' unit normals have a dot product within this of 1 (unit: 1 - cos). Why: the
// edge's two prisms leave out only a sliver r a^2 / 8 thick for a bend of a radians, here
// 1.25e-10 r; the exact boundary's coplanar pieces differ in normal by a few ulps, far below.
inline constexpr double kMinkowskiFlatEdgeCos = 1e-9;
// ... and takes a mesh as convex when no vertex is farther than this fraction of its size
// above any of its triangles' planes (unit: relative). Why: the vertices of a convex mesh made
// by trigonometry (a BOSL2 spheroid) lie on their faces' planes to ~1e-15 of the size; a
// mesh dented by less than 1e-9 of its size is convex to every printer and every tolerance.
inline constexpr double kMinkowskiConvexRel = 1e-9;
// ... and sums with a sphere exactly when its transform keeps it a ball: the lengths of the
// matrix's axes agree, and their dot products vanish, to this fraction of their squares
// (unit: relative). Why: rotations built from OpenSCAD's sin and cos are orthogonal to ~1e-16;
// an ellipsoid within 1e-12 of a ball is that ball to every tolerance downstream.
inline constexpr double kBallTransformRel = 1e-12;

// Meshing refines its grid until the *sampled* mesh-surface distance is within this fraction
// of the tolerance (unit: relative). Samples (vertices, centroids, edge midpoints, a grid of
// surface points) find the maximum to within ~10-20% on the samples; 0.8 leaves that margin so
// an independent sampling (csgray compare, another tool) also finds the mesh within T.
inline constexpr double kMeshMeasureMargin = 0.8;

// A distance sample (csg/mesh/MeshDistance.h) takes its first line's answer (along the mesh or
// surface normal) only when it is within this fraction of the tolerance (unit: relative to T);
// above it, the other lines are tried and the smallest answer kept. Every line's answer bounds
// the distance from above, but the normal line of a point near a crease can run almost along
// the surface: on csg_grid3 at cell 0.021 (T = 0.02), ~640 of 12.4 M mesh samples took 0.8T-T
// from their first line under T, and none measures over 0.5T along its best line; those loose
// bounds above the 0.8T margin kept refining. Samples past a quarter of T are ~0.2% of all.
inline constexpr double kDistanceFirstLineFraction = 0.25;

// An export of a part with curved leaves first facets them (io/ChordFaceting.h) so that no
// face stands more than this fraction of the tolerance off the exact surface, and writes that
// polyhedron's exact boundary (unit: relative to T). Why: where faceted leaves meet, the
// boundary moves by about their deviation (more where they meet at a grazing angle), and the
// measurement must find it within kMeshMeasureMargin (0.8 T): half of T leaves that margin.
inline constexpr double kFacetDeviationFraction = 0.5;
// ... tried up to this many times after the first (unit: attempts). Why: a faceting that misses
// four times has curves meeting at grazing angles that the grid serves better, and each
// attempt costs a full boundary.
inline constexpr int kFacetAttempts = 3;
// Where a leaf curved both ways meets one curved one way (a sphere and a bore), a faceting that
// misses is tried first with the one-way leaf at this share of the deviation (unit: relative).
// Why: the rim moves by both leaves' deviations, amplified by the angle between them (Debian's
// example001, 60-degree rims: 2.3 d balanced), and a one-way leaf's faces grow as 1 / sqrt(d)
// where a sphere's grow as 1 / d, so its deviation is the cheaper one to cut. example001 at
// T = 0.273 (Manifold's distance): 1 912 triangles by shrinking both, 1 208 at 0.5, 1 288 at
// 0.35; parts whose first faceting measures within the margin never take it (applied from the
// first attempt, 0.5 cost Debian's children 7.6 %, pawn 12 %, knob 5 %; those and the 0.35
// from a one-off build, bench/README.md "Rims where a sphere meets a bore").
inline constexpr double kFacetOneWayShare = 0.5;
// A balanced faceting (csg::FacetFit) that measures more than this many times its deviation
// off keeps material the exact part lacks (a skin of the equator's ring over a cut flush with
// it; a balanced sphere stops at its poles' planes, io/ChordFaceting.cpp), and the
// inscribed fit is tried instead (unit: relative to the deviation). Why: the faceting's own
// error, where curves meet at rims, measured up to about twice the deviation (csg_grid3's
// parts, --curves exact: 1.66 balanced, 1.85 inscribed); a skin measures its distance to the
// cut's walls, or nothing within reach.
inline constexpr double kFacetSkinFactor = 3.0;
// When a faceting's measured distance m says how far to move its deviation d, the next one is
// d times this fraction of the margin over m (unit: relative). Why: the distance grows about
// linearly with the deviation; 0.8 keeps a fifth of the margin for the next measurement, since
// after a step a faceting measured up to 1.1 times as far off as that line expects where curves
// meet at rims (samples/emblem.scad and gem.scad missed with 0.9).
inline constexpr double kFacetSlackTarget = 0.8;
// A miss that is not a skin is tried again finer by that rule, the factor kept between these
// (unit: relative). Why: at most 0.8 so that every retry is finer, at least 0.25 so that one
// wild sample does not spend all the faces.
inline constexpr double kFacetFinerMin = 0.25;
inline constexpr double kFacetFinerMax = 0.8;
// A faceting that measures within the margin is tried coarser by that rule, at most
// kFacetSlackMaxGain times the deviation, and only for a gain of kFacetSlackMinGain or more
// (unit: relative). Why: the measured distance sits near the deviation (T/2), so about 0.3 T of
// the margin (0.8 T) is unspent, and faces grow with 1 / sqrt(deviation) per curved direction;
// below a 1.25-fold gain the attempt costs more time than it saves triangles.
inline constexpr double kFacetSlackMaxGain = 2.0;
inline constexpr double kFacetSlackMinGain = 1.25;
// ... again from each coarser faceting kept, up to this many in all (unit: attempts). Why: a
// faceting whose bound is far from what it measures (a twisted side, whose quads' bound counts
// the worst of a whole edge) still measures well under the margin at twice its deviation; a
// chord rule's faceting measures near its deviation and stops after one.
inline constexpr int kFacetSlackAttempts = 3;

// A mesh's corners and edge midpoints are distance-sampled at the point this fraction of the way
// towards their triangle's centroid (unit: relative to the distance to the centroid;
// MeshDistance.cpp): a point of the mesh too, so the figure stays an upper bound of the distance
// at a point of the mesh. Why: where the mesh follows the part's edges (an exact polyhedral
// mesh), a line through the corner itself only grazes the solid and its answer is loose by up to
// T; from inside the triangle, the line along its normal crosses the face at t ~ 0. The step must
// be far above the rounding of the mesh's coordinates (a GLB, STL or 3MF holds floats: ~1e-7 of
// the part, up to 1e-5 of a small triangle) and leave the samples where they were to any
// tolerance: 1e-3 of a triangle's size is both (csg_grid3's exact mesh read back from its GLB
// measured 0.0032, a grazing line, with 1e-6; 1.8e-7 with this).
inline constexpr double kDistanceSampleInset = 1e-3;

// A distance sample that no line resolves within T (a point on an edge where two solids only
// touch, or on a convex corner, where lines see fused or zero-length spans) is measured again
// from a point shifted by this fraction of T in a direction of no symmetry, and the shift is
// added to the answer (unit: relative to T; MeshDistance.cpp). Why: the shift must be far above
// coordinate rounding (~1e-16 of the part) for lines from there to see the solids apart, and
// what it adds to the distance must be negligible against the margin of kMeshMeasureMargin
// (0.2 T): 1e-3 T is both.
inline constexpr double kDistanceShiftFraction = 1e-3;
// ... and, while that finds nothing within T, from points shifted ten and a hundred times
// farther, up to this fraction of T (unit: relative to T). Why: where solids touch tangentially
// (Debian's example017: a disc's rim against a flat wall) the gap beside the contact opens as
// s^2 / (2 r) at a shift s, 1e-10 at 1e-3 T there, which the span merge fuses; at 0.1 T it is
// 1e-6, a gap every line sees, and the 0.1 T it adds stays well under the margin.
inline constexpr double kDistanceShiftMaxFraction = 0.1;
// A distance sample whose bound may be the maximum is tightened by lines along the surface
// normal where its best line met the surface, up to this many, each from the last one's hit
// (unit: lines; MeshDistance.cpp). Why: on a smooth surface the first such line runs through
// the foot point to within the surface's turn over the gap, and a second from its hit corrects
// that turn once more (mesh_test: a point 0.1 off sphere(1) read 0.1257 by the fixed lines,
// within 1e-5 of the truth after the fan and these); one or three were not measured.
inline constexpr int kDistanceFootSteps = 2;

// How far apart dual contouring keeps vertices that must stay distinct points once written as
// float to a GLB (unit: multiples of the cell size h; a cell thinner than 4x this, one through a
// thin gap, uses a quarter of its width instead): a crossing is kept this far inside its grid
// edge, and sheet vertices this far inside their cell and from each other. Why: float's relative
// 6e-8 of a coordinate is ~1e-5 h for parts ~100 h across, so 1e-3 h stays clear of that, and
// each of these moves the mesh by at most 1e-3 h.
inline constexpr double kMeshVertexSeparation = 1e-3;

// A crease vertex on a cell face closer than this to a crossing on the face is dropped, the face
// curve then runs straight between its crossings (unit: multiples of h; a quarter of a thinner
// cell's width, as for kMeshVertexSeparation). Such a vertex only adds a sliver triangle, and a
// sliver this short folds onto its neighbour within the self-intersection check's coplanarity
// tolerance (kSelfIntersectionContactRel) at a few degrees: csg_grid at T = 0.013 had two
// crease vertices 1.1e-3 h from the crossing of one edge, on its two faces, on the same side
// (the surface runs almost along the edge), so the cell's ring doubled back there and no place
// of its sheet vertex unfolded it. Dropping it moves the face curve by at most this much.
inline constexpr double kCreaseVertexSeparation = 1e-2;

// Self-intersection check (csg/mesh/MeshCheck.h): two triangles count as crossing only when
// each reaches through the other's plane, and their overlap is longer, by more than this
// fraction of the mesh's largest coordinate magnitude; a triangle within it of the other's
// plane is coplanar with it (unit: relative). Why: a GLB
// stores positions as float, rounded by up to 6e-8 of the largest coordinate, so two faces that
// touch exactly (a vertex on a face, an edge along an edge) can come back crossing by a few
// float ulps; 1e-6 is ~16 of them. Meshing keeps distinct vertices 1e-3 h apart
// (kMeshVertexSeparation), 10^3 above this for parts up to ~10^3 h across, so a real fold of
// the mesh is not hidden by it.
inline constexpr double kSelfIntersectionContactRel = 1e-6;

// Dual contouring's unfolding (csg/mesh/UnfoldVertices.h) and the simplifier's crossing rule
// (csg/mesh/Simplify.h) test their triangle pairs stricter than findSelfIntersections does, by
// this factor both ways: a contact tolerance this many times smaller (depths, overlaps,
// slivers) and coplanarity this many times looser (unit: ratio). Why: they test the double
// mesh, the check often runs on the GLB's floats, rounded by up to 1/16 of the tolerance; on
// csg_grid3 (T = 0.05) a sliver folded onto its neighbour, tilted from its plane by just over
// the tolerance (a contact in double), came back from the GLB within it, a coplanar overlap.
inline constexpr double kUnfoldCheckMargin = 2.0;

// The unfolding's winding certificate (csg/mesh/UnfoldVertices.cpp): the angles of a vertex's
// triangles, seen along their mean normal, must add up to 2 pi within this (unit: radians) for
// its star to count as embedded without testing its pairs. A star that winds twice is 2 pi
// off, one that folds at least twice its folded angle. Why 1e-9: the sum of up to 32 atan2
// terms rounds by ~1e-14, far below it; a fold below it tilts a triangle out of its
// neighbours' plane by under 1e-9 of its size, inside the check's coplanarity tolerance
// (kSelfIntersectionContactRel), so the pairwise test would not report it either.
inline constexpr double kFullTurnSlack = 1e-9;

// Two crossings of one grid edge whose normals are further apart than this (unit: cosine,
// about 105 degrees) bound a wall or gap thinner than the cell, and meshing adds a grid plane
// between them (csg/mesh/ThinFeatures.h). A line grazing a convex surface also crosses one edge
// twice, but there the normals nearly agree (they differ by more than 90 degrees only on a
// surface whose radius is below the cell), and two faces meeting at a box edge are 90 apart:
// neither needs a plane, the cell's QEF vertex follows them.
inline constexpr double kThinFacingCos = -0.25;

// Thin walls and gaps narrower than this (unit: multiples of the grid spacing h) get no plane
// of their own: each would cost a plane through the whole part, and a fused wedge-shaped gap
// that narrow reaches only that width times the wedge's cotangent into the part.
inline constexpr double kThinMinWidth = 0.002;

// Mesh refinement stops when a pass cut the measured error by less than this fraction of what
// the linear law (error proportional to the cell size) promised for its finer spacing (unit:
// relative). Errors left by gaps narrower than any affordable cell, or by the measurement's
// own floor, do not shrink with h; a quarter still lets a pass whose errors are only partly
// of that kind go on, and each further pass costs ~2.5x the previous one.
inline constexpr double kMeshStallFraction = 0.25;

// Simplifying a grid mesh (csg/mesh/Tessellate.cpp) may spend at least this fraction of the
// tolerance even when the grid's mesh already measures close to the margin (unit: relative to
// T): the grid mesh's errors sit at a few creases, collapses that would add to them are caught
// by measuring the result (and rejected), while flat and gently curved regions elsewhere coarsen.
inline constexpr double kSimplifyMinBudget = 0.1;

// The fallback simplification budget, and the only one when the grid's mesh is already over
// the margin (unit: relative to T): only collapses within plane rounding of exactly flat regions
// and straight creases pass (coordinates carry ~1e-16 relative rounding, 1e-6 T is far above
// it). They leave the surface where it was, so the simplified mesh is as far from the part as
// the grid's; measuring it again only samples other points of that same surface, so it is held
// to T (or the grid mesh's own figure), not to the margin.
inline constexpr double kSimplifyFlatBudget = 1e-6;

// A collapse may turn a triangle of its fan by at most this much (unit: cosine; 60 degrees):
// more means it folds the surface over a neighbour rather than flattening a gently curved patch.
inline constexpr double kSimplifyMaxFanTurnCos = 0.5;

// Neighbouring mesh triangles whose normals differ by more than this meet at a crease, and the
// exported normals are split there (unit: degrees). 40 is within the 30-45 most tools use for
// "auto smooth": a part's designed edges (90 degree box edges, 45 degree chamfers) split, while
// a mesh within tolerance of a curved surface turns by far less between neighbours.
inline constexpr double kShadingCreaseDegrees = 40.0;

// The algebraic patch methods (primitives/patch/Groebner.h, Resultant.h). The Groebner
// reduction's small-value rule: after each elimination step (f -= k m g) a coefficient whose
// magnitude is at most this fraction of the step's scale max(|f|, |k| |g|) is zero (unit:
// relative). Why: the article computes in floating point, where a term that cancels exactly
// in exact arithmetic leaves a residue of a few ulps of the step's scale; kept, it becomes a
// spurious leading term (a wrong basis, often a constant: 1 in G, a false miss). A chain of
// reductions (up to ~30 steps on a bicubic pair) grows the residue to ~1e-13; 1e-10 keeps a
// margin of 10^3. The price, and the method's documented breakdown: a genuine coefficient
// below 1e-10 of its step's scale is dropped too (bench/reports/patches.md).
inline constexpr double kGroebnerSmallRel = 1e-10;

// A candidate (u, v) of the algebraic methods is a common root of the two plane equations
// when |F_k(u, v)| is within this fraction of the sum of |terms| of F_k there (unit:
// relative). Why: u comes from an eliminant whose coefficients carry the reduction's rounding
// (up to ~1e-8 relative in the hard cases measured), v from a basis element evaluated there;
// a candidate that is not a root (a root of a v-polynomial with no partner) leaves a residual
// of the order of the terms themselves. 1e-6 sits between the two.
inline constexpr double kPatchResidualRel = 1e-6;

// Two crossings of one patch found by the algebraic methods whose (u, v) differ by at most
// this in both parameters are one point (unit: patch parameter). Why: a tangent ray gives a
// double root of the eliminant that the solvers report twice, and two basis elements can give
// the same v; double roots in u are found only to ~sqrt(ulp) = 1e-8, so 1e-7 merges them while
// two genuine crossings that close are a tangency at the span rule's resolution anyway.
inline constexpr double kPatchSamePointParam = 1e-7;

// The algebraic methods' fallback for v at a near-double root u (PatchAlgebra.h,
// crossingsFromPlaneRoots). Two roots of the eliminant (or resultant) within this of each other
// are a near-double root: there v from the basis element or Bezout null vector is
// ill-conditioned, so v comes from the plane equations, polished in (u, v), and the result
// counts only when u moved by at most this (unit: patch parameter). Why: such a root is found
// only to ~sqrt of its coefficients' relative error, up to 1.6e-6 measured on the paraboloid
// (its two roots 1.6e-6 apart); a polish that moves u further has set off towards another
// crossing (0.2 away in the case that made this rule). 1e-4 keeps a 60x margin on the first,
// rejects the second, and leaves the fallback's cost to the rare rays that need it.
inline constexpr double kPatchRootDriftParam = 1e-4;

// Bicubic Bezier patches (primitives/patch/). A crossing's (u, v) may lie this far outside
// [0, 1]^2 and still count, then clamped onto it (unit: patch parameter). Newton converges to
// a root on an edge or corner (a ray through a shared edge, the teapot's poles) to within a
// few ulps, on either side; 1e-9 keeps a 10^6 margin over that, yet moves a point by at most
// 1e-9 of the patch size, the same as span-end coincidence (kCoincidentRel).
inline constexpr double kPatchParamSlack = 1e-9;

// 2-D Newton on a patch stops when a step moves (u, v) by less than this (unit: patch
// parameter, max norm). Why: near a simple root Newton doubles the correct digits per step, so
// a step of 1e-13 means the iterate is already within ~1e-26 of what this step size can
// express; t then carries only the rounding of evaluating S (a few ulps of the patch size).
inline constexpr double kPatchNewtonStep = 1e-13;

// Where 2-D Newton meets a singular Jacobian (the ray tangent to the patch, or a degenerate
// point), (u, v) is a root only if the residual, the point's distances from the ray's two
// planes, is at most this many ulps of the patch size (unit: kUlp times the patch's box
// diagonal; primitives/patch/RayPlanes.cpp). Why: at an exact root the residual is rounding
// alone, about ten ulps of the points' magnitude from de Casteljau's evaluation and the
// projection; 64 covers that with margin for a patch whose size is of the order of its
// distance from the frame's origin, and a point ~1e-14 of the patch off the ray is no root.
inline constexpr double kPatchSingularResidualUlps = 64.0;

// Crossings of one patch set whose points on the ray are closer than this fraction of the
// set's bounds diagonal are one crossing (unit: relative to the set's size). Why: a ray
// through the shared edge of two patches (or a pole shared by four) is found by each of them,
// at t that differ by the few-ulp rounding of each patch's Newton polish; 1e-9 covers that by
// 10^5 and is the span coincidence rule's size (kCoincidentRel), so two distinct crossings
// closer than this would have been fused as a sliver by the CSG merge anyway.
inline constexpr double kPatchDedupeRel = 1e-9;

// PatchSet::normal takes (u, v) from a crossing of the last spans() call whose point on the
// line lies this close to the shaded point (unit: relative to the set's bounds diagonal). Why:
// the shaded point is the same crossing computed again (the world hit mapped into the local
// frame), a few ulps away; two crossings of one patch this close are one point to shading,
// and Gauss-Newton from either (u, v) converges on p. Same size as kPatchDedupeRel.
inline constexpr double kPatchCarriedPointRel = 1e-9;

// Bezier clipping hands a region to Newton polish once it is narrower than this in both u
// and v (unit: patch parameter). Why: clipping converges quadratically near a simple root, so
// regions shrink to this in a few steps; from 1e-6 Newton needs 2-3 steps. Smaller costs
// clipping steps (each a de Casteljau restriction) that Newton does faster; larger risks two
// close roots sharing one region (one would be lost).
inline constexpr double kPatchClipWidth = 1e-6;

// Subdivision + Newton: a sub-patch is flat when its control points lie within this fraction
// of its own bounds diagonal from the plane of its corner diagonals (unit: relative). Why: a
// line meets a patch this close to a plane at most once unless it grazes it within ~0.1
// degrees, and Newton from the centre of such a patch stays inside its basin; 1e-3 reaches
// it in ~5 halvings per direction on the teapot.
inline constexpr double kPatchFlatRel = 1e-3;

// Subdivision + Newton keeps a root found from a flat piece's centre when it lies inside the
// piece, or outside it by at most this fraction of the piece's width (unit: relative to the
// piece's u and v widths), plus kPatchParamSlack (primitives/patch/NewtonSubdivision.cpp). Why:
// a root on the edge two pieces share is found by both, each a few ulps to either side of the
// edge, and must not be rejected by both; 1e-6 of the piece keeps that root (the duplicate is
// merged, kPatchDedupeRel) while a root farther out is left to the piece it lies in, which
// finds it itself. The absolute slack covers the smallest pieces, where 1e-6 of the width is
// below Newton's last step (kPatchNewtonStep).
inline constexpr double kPatchOwnMargin = 1e-6;

// Bezier clipping widens each clipped parameter range by this fraction of the region on both
// sides (unit: relative to the region being clipped). Why: the hull's crossing with the ray is
// computed from rounded plane distances, so a root exactly on a clip boundary could fall a
// few ulps outside it and be lost; 1e-7 covers distances rounded to ~1e-9 of their spread and
// slows convergence by nothing measurable (a clip shrinks a region by orders of magnitude).
inline constexpr double kPatchClipMargin = 1e-7;

// A patch normal dS/du x dS/dv shorter than this fraction of max(|dS/du| |dS/dv|, size^2)
// is degenerate (unit: relative; size is the patch's box diagonal): collinear partials, or a
// partial that is rounding noise (at a pole dS/dv is ~1e-16 of the size, not 0), where the
// direction is taken as the limit from inside the patch instead. Why 1e-10: there the cross
// product has lost ~6 of double's 16 digits to cancellation, still a fine direction; a
// rounding-noise partial gives ~1e-16, far below.
inline constexpr double kPatchNormalDegenerateRel = 1e-10;

// A mesh read for comparison (io/mesh/MeshFile.h) may not have a vertex coordinate larger in
// magnitude than this (unit: the file's own). Why: compare sums triple products of
// coordinates for the volume and squares them for distances; at 1e30 a cube of a coordinate
// is 1e90, so a billion triangles stay ~10^209 below double's overflow, where 1e300 gave
// inf - inf = NaN. No part in any unit comes near it (the observable universe is ~1e27 m).
inline constexpr double kMeshCoordinateMax = 1e30;

// A mesh primitive's edge side, fl(fl(a) - fl(b)) for the exact a - b (primitives/
// Polyhedron.cpp), has the exact sign when its magnitude exceeds this fraction of |a| + |b|
// (unit: relative). Why gamma(4): the two products and the difference round once each, an
// error of at most (2u + u^2)(|a| + |b|) with u = kUlp / 2, and gamma(4) ~ 4u covers it twice;
// below it the sign is computed exactly (error-free products), so the value only decides how
// often that slower path runs, never an answer.
inline constexpr double kEdgeSignFilter = gamma(4);

// A mesh primitive's BVH boxes are each triangle's box widened by this fraction of the mesh's
// box diagonal on every side (unit: relative). Why: the crossing test decides on the vertices
// projected into the ray's frame, each coordinate a few roundings (about 8 ulps) of the
// distance from the ray's origin, which lies on the mesh's box, to the vertex: at most the
// diagonal. A triangle the test counts as crossed is therefore within ~16 ulps of the diagonal
// of the exact line, and a box that misses the line by less must not cull it, or the line would
// lose one crossing of a pair. 1e-12 (~4500 ulps) covers that with a wide margin and is still
// ~10^9 below any feature a part resolves; it only lets a few more boxes be opened.
inline constexpr double kMeshBoxMarginRel = 1e-12;

// 2-D boundaries (csg/derived/Boundary2D.cpp): two points of the outlines of a 2-D shape closer
// than this fraction of the shape's size (max(1, largest |coordinate|)) are one point: a
// crossing that near a segment's end is that end, and a segment parallel to another that near
// it lies on it (unit: relative). Why: the crossings come from a few operations on coordinates
// (a 2x2 solve, a square root for a circle), so they err by ~10^2 ulps of the size, 10^4 below
// this; and no outline a part draws on purpose has features 10^-10 of its size apart.
inline constexpr double kBoundaryPointRel = 1e-10;

// Whether a piece of an outline between two crossings bounds the shape is read at two points
// this fraction of the shape's size to either side of its middle, or 1/20 of the piece's
// length if that is less (unit: relative). Why: 100 times kBoundaryPointRel, so the two points
// lie on the two sides of the piece whatever the rounding of its crossings, yet no other
// outline passes between them unless it lies on the piece (then they agree, see Boundary2D.h).
inline constexpr double kBoundarySideRel = 1e-8;

// Two pieces of one circle next to each other in a 2-D boundary's contour are one arc when
// their sweeps add up to at most a whole turn plus this, and a whole circle when they add up to
// a whole turn less this or more (unit: radians). Why: each sweep comes from atan2 of the
// piece's ends, within a few ulps of 2 pi (~10^-15), 10^6 below this; and no arc a part draws
// on purpose stops 10^-9 radians short of a whole turn.
inline constexpr double kArcSweepSlack = 1e-9;

// An arc's box (primitives/SegmentCarrier.cpp) is widened by this fraction of its size (the
// larger of its centre's coordinates and its half-axes). Why: the arc's stored ends may stand a
// few ulps (~10^-16 relative) off its ellipse, being its neighbours' very doubles, and the
// angles of its extremes are rounded: 100 times that covers both, while keeping a piece of a
// circle's box its own (a box only prunes; the crossings are exact).
inline constexpr double kArcBoxGuardRel = 1e-14;

// Elliptic arcs and Beziers, whose offsets are no circles or lines, are replaced by chords no
// farther than this fraction of the shape's size from the curve before an offset or hull
// (unit: relative). Why: 1e-7 of a 100 mm part is 10 nm, 150 times finer than OpenSCAD's own
// 2^-16 grid at that size, while a glyph's quadratic of 10 mm needs only tens of chords.
inline constexpr double kFlattenRel = 1e-7;

// projection() and resize() (csg/section/Projection.h): a leaf that is not polyhedral is made
// a closed mesh within this distance of its surface, relative to the diagonal of its bounds
// (unit: length / length). 5e-4 puts a sphere's section within 5e-4 * 2 sqrt(3) r ~ 1.7e-3 r
// of its circle, finer than OpenSCAD's default facets of a sphere of any size (a sagitta of at
// least 5e-3 r), at ~6k triangles for an inscribed sphere: small enough that a shadow's face
// method (faces x triangles) stays within a second for a sphere minus a few cones.
inline constexpr double kLeafMeshToleranceRel = 5e-4;

// Vertices this close to a face's plane count as on it when a shadow cuts the part by that
// plane (unit: length, relative to the part's largest coordinate). The plane through a
// triangle is computed from one corner; its other corners, and the other triangles of the
// same planar face, then sit a few rounding errors off it (~1e-16 relative), and counting
// them on the plane keeps the pieces of neighbouring faces edge to edge. 1e-12 (~4500 ulps)
// is ~10^9 below any feature a part resolves.
inline constexpr double kOnFacePlaneRel = 1e-12;

// A twisted or unevenly scaled extrusion's mesh (io/ExtrusionMesh.cpp) cuts its outline's edges
// into pieces whose cut points stand a few rounding errors (~1e-16 relative) off the line
// through the edge's ends; its caps' ear clipping takes a corner this close to that line as on
// it, so no ear is cut at a cut point (it would be a sliver of no area) (unit: length, relative
// to the outline's largest coordinate). 1e-12 (~4500 ulps) covers the rounding and is ~10^9
// below any deviation an export asks.
inline constexpr double kCutPointStraightRel = 1e-12;

// glibc's cos and sin are within this of the exact value at any double argument (unit:
// absolute, the values lying in [-1, 1]). Why: glibc documents a maximum error of 1 ulp for
// both on x86-64 (its manual's "Errors in Math Functions"), and an ulp of a value in [-1, 1] is
// at most kUlp; twice that is a margin against a libm that misses by a little more. Interval
// enclosures of cos and sin (solvers/Interval.h) widen by it.
inline constexpr double kLibmTrigError = 2 * kUlp;

// Twisted extrusions (primitives/TwistedExtrusion.h). A line's chord through the solid is
// first cut into pieces over which the twist turns the line's image by at most this angle
// (unit: radians). Why 1: over a radian the image's curvature changes little, so the bounds on
// its first and second derivatives that the isolation uses stay within a small factor of the
// true values, and a piece rarely holds more than one turn of a segment's function; much
// smaller only multiplies the pieces every segment must test, much larger makes the first
// pieces' bounds so loose that they are split anyway.
inline constexpr double kSweepPieceAngle = 1.0;

// The least angle a twisted extrusion's first pieces turn by, however small its segments are
// against its radius (unit: radians). Why: a first piece turns by about its outline's median
// segment extent over its outer radius, so that a piece's image sweeps about one segment and
// a segment meets few pieces (example020's spring, screw and nut render 2.3x, 4x and 4x
// faster than with 1-radian pieces; half that angle is 1.4-1.6x slower, twice it 1.1-1.3x);
// below 1/32 a piece's own enclosure costs more than the halvings it saves.
inline constexpr double kSweepMinPieceAngle = 1.0 / 32.0;

// The most first pieces a twisted extrusion cuts a chord into (unit: pieces). Why: twist is
// unbounded in the language (OpenSCAD accepts 1e6 degrees); past this count the pieces turn
// by more than kSweepPieceAngle, which costs more halvings, never a root, and the work per ray
// stays bounded. 4096 pieces cover 650 turns over a full-height chord.
inline constexpr int kSweepMaxFirstPieces = 4096;

// A twisted extrusion halves a piece at most this many times (unit: halvings of a first
// piece). Why 60: a first piece is at most the chord, and 2^-60 of it is below the double
// resolution of any parameter in it (2^-52 relative); a piece still undecided there is given
// up as a cluster (its two ends become candidates), which is exact to that width.
inline constexpr int kSweepMaxDepth = 60;

// Below this depth a twisted extrusion splits an undecided piece where its segment's function
// G turns (where G' vanishes, when G'' has a proven sign there), and from it on at the
// midpoint (unit: splits). Why 8: a piece split at its turn usually has two monotone parts at
// once; one still undecided after 8 such splits is near a tangency, where the turn and a root
// nearly meet and halving is the sure way down. Any split point is correct: this only saves
// work.
inline constexpr int kSweepTurnSplitDepth = 8;
// ... and finds that turn with this many steps of Newton's method on G', safeguarded by
// bisection (unit: iterations). Why 6: the turn is only a split point, not a result, and
// Newton converging quadratically from the secant's estimate is within a fraction of a percent
// of the piece by then; more steps would refine what no answer depends on.
inline constexpr int kSweepTurnIterations = 6;

// A twisted extrusion tests at most this many pieces per segment and line (unit: pieces).
// Why: it bounds the work on any line whatever the twist and the outline (the pieces left
// when it runs out become candidates at both ends, exact to their width); a simple root
// costs a handful of pieces and a tangency about 2 per level of kSweepMaxDepth, so only a
// line with thousands of near-tangencies along one segment's sweep could run out.
inline constexpr int kSweepMaxPieces = 1 << 14;

// A twisted extrusion's bounding cylinder (radius: the outline's farthest box corner from the
// axis times the largest scale) is widened by this fraction (unit: relative). Why: the radius
// and the line's chord through the cylinder are rounded (a few ulps); the solid must lie
// strictly inside the chord so that the chord's ends are outside it, and 1e-9 covers the
// rounding by 10^6 while adding nothing but a little empty chord.
inline constexpr double kSweepBoundsMarginRel = 1e-9;

// A crossing found on a segment's carrier curve (its line, ellipse or implicit Bezier curve)
// is kept as a candidate when its profile point lies in the segment's box widened by this
// fraction of the box's size plus its distance from the origin (unit: relative). Why: the
// point carries the root's and the map's rounding, ~1e-15 relative; a crossing at a segment's
// end must survive it, and 1e-9 does by 10^6, while a spurious candidate (a crossing of the
// carrier off the segment that passed) costs only one more midpoint test.
inline constexpr double kSweepCandidateSlackRel = 1e-9;

// An outline Bezier whose control points lie within this fraction of their extent from the
// line through the farthest two is carried by that line, and a cubic whose third-degree
// coefficient is this small relative to its extent by the quadratic it then is (unit:
// relative). Why: the implicit equation of a flatter curve cancels to this fraction, so it
// carries less information than the straight carrier, whose error is the curve's distance from
// it: 1e-12 of the curve, 1000x below kCoincidentRel. (Exactly flat curves make the implicit
// equation a power of the line's, which has no sign change to isolate.)
inline constexpr double kFlatCurveRel = 1e-12;

// Newton's method, safeguarded by bisection, polishes a bracketed crossing of a twisted
// extrusion in at most this many steps (unit: iterations). Why: every step at least halves the
// bracket when Newton's step is refused, and 64 halvings take any bracket below double
// resolution, so the bound is never what stops a simple root (4 to 6 steps).
inline constexpr int kSweepNewtonIterations = 64;
// ... and stops when a step or the bracket is at most this many ulps of |t| (unit: ulps of the
// line parameter, measured at |t| of the world-local line). Why: t = tm + tau is rounded to an
// ulp of |t| when it is formed, so a finer root would be lost there; 4 leaves the last Newton
// step (which is then below an ulp or two) room to land.
inline constexpr double kSweepRootStepUlps = 4.0;

}  // namespace csg::tol
