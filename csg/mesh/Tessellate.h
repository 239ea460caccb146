// A scene to a triangle mesh within a distance tolerance. A part whose leaves are all polyhedra
// is a polyhedron: it gets its exact boundary (PolyhedralBoundary.h), measured like any mesh.
// Every other part: tri-dexel Hermite data on a uniform
// grid with planes added through walls and gaps thinner than a cell (ThinFeatures.h), manifold
// dual contouring (with flat blocks of cells merged, the octree of DualContour.h, when
// TessellateOptions::adaptive is on), and a measure-and-refine loop on the grid spacing. The
// loop measures the merged mesh, so the octree's own error (at most ~kOctreeFlatFraction T per
// block, see Tolerances.h) is refined away like the grid's.
//
// The tolerance rule. For a surface of smallest curvature radius R, a triangle spanning a
// cell of edge h (diameter sqrt(3) h) deviates from it by at most (sqrt(3) h)^2 / (8 R), so
// h = sqrt(8 R T / 3) meets tolerance T. R is not known for a general part, so the first pass
// assumes R = kReferenceRadiusFraction of the bounds' diagonal; then the mesh-to-surface
// distance is *measured* (MeshDistance.h: every vertex, centroid and edge midpoint, along the
// mesh normal and other lines; and surface to mesh, which sees a chamfered or lost feature
// that every mesh point is close to) and h shrinks with a 0.85 safety factor by T / measured
// while the mesh-to-surface distance misses (a linear law: the worst errors sit at curved
// creases such as a hole's rim, where a cell's QEF vertex is clamped or falls back to the mass
// point, and those shrink in proportion to h), and by sqrt(T / measured) when only the
// surface-to-mesh distance does (a chord's sagitta, or a fused gap that falls in steps) until
// the measurement is within T, the cell cap is reached, maxPasses passes have run, or a pass
// stalled on a part with thin walls or gaps (after a pass that missed T, the error fell by much
// less than the spacing: see tol::kMeshStallFraction).
//
// Then the grid's mesh is coarsened where it is flat or gently curved (Simplify.h) within the
// error budget the grid left (kMeshMeasureMargin T minus the measured error, at least
// tol::kSimplifyMinBudget T; none when the grid's mesh is already over the margin), and measured
// again both ways; a simplified mesh that measures worse than the margin (or than the grid's
// mesh, when that was already over) is retried with flat regions and straight creases only
// (held to T: the surface does not move), then dropped for the grid's mesh. A grid mesh over
// the margin after the cell cap or a stall stopped refining is not simplified at all (the
// flat-only pass costs more than it saves on such a mesh).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "csg/Scene.h"
#include "csg/mesh/Distribute.h"
#include "csg/mesh/DualContour.h"
#include "csg/mesh/MeshDistance.h"
#include "csg/mesh/PolyhedralBoundary.h"
#include "csg/mesh/ThinFeatures.h"
#include "csg/mesh/TriangleBvh.h"
#include "csg/mesh/TriangleMesh.h"

namespace csg {

// Surface samples of the surface-to-mesh measurement: lines per axis along each of x, y, z.
inline constexpr int kSurfaceRaysPerAxis = 128;

// How a faceted curve sits on the exact one. Inscribed: its vertices on the curve, its faces
// inside. Balanced: scaled out until its vertices stand as far outside as its faces inside, so
// the same faces stand half as far off; but a curve's extremes then stand out of the exact
// solid, and a cut flush with one (a pocket from a sphere's pole down) keeps a skin over it.
enum class FacetFit { Inscribed, Balanced };

// A polytope inscribed in a curve of radius r has its vertices on the curve and its faces up to
// r (1 - c) inside it (c r: the distance of its nearest face plane from the centre or axis).
// Balanced, it is scaled by 2 / (1 + c) about that centre or axis: its vertices stand
// r (1 - c) / (1 + c) outside and its nearest faces as far inside, and every point between (the
// polytope is convex and star-shaped about the centre). Returns the scale for the fit, or 0
// when the faces would stand more than `deviation` off a curve of radius r.
inline double facetFitScale(FacetFit fit, double c, double r, double deviation) {
    if (fit == FacetFit::Inscribed) return r * (1.0 - c) <= deviation ? 1.0 : 0.0;
    return r * (1.0 - c) / (1.0 + c) <= deviation ? 2.0 / (1.0 + c) : 0.0;
}

// A part's curves faceted to a deviation and fit (TessellateOptions::facetCurves); the leaves
// curved one way only take oneWayShare (in (0, 1]) of the deviation in a part that also has
// leaves curved both ways (mixedCurvature), the whole of it otherwise.
struct CurveFaceter {
    std::function<std::optional<Scene>(double deviation, FacetFit fit, double oneWayShare)> facet;
    // The part has leaves curved both ways (spheres, tori, revolved arcs) and leaves curved one
    // way only (cylinders, cones, extruded arcs): a faceting that misses is tried once more at
    // the same deviation with the one-way leaves finer (tol::kFacetOneWayShare) before the
    // deviation shrinks for all.
    bool mixedCurvature = false;

    explicit operator bool() const { return bool(facet); }
    std::optional<Scene> operator()(double deviation, FacetFit fit, double oneWayShare) const {
        return facet(deviation, fit, oneWayShare);
    }
};

struct TessellateOptions {
    // Largest allowed mesh-to-surface distance (world units); <= 0 means 1/500 of the bounds'
    // diagonal.
    double tolerance = 0.0;
    // Cap on the grid's cells (the work and memory of one pass grow with it).
    uint64_t maxCells = uint64_t(1) << 24;
    int maxPasses = 4;
    // Merge flat blocks of cells into one vertex each while contouring (the octree of
    // DualContour.h, flat to tol::kOctreeFlatFraction T): far fewer triangles on flat and gently
    // curved faces, fine cells at creases, thin gaps and curved patches. Off by default: blocks
    // next to folds are split in further rounds (no self-intersections on the samples and
    // octree_test's random parts), and on csg_grid3 those rounds cost clearly more export time
    // than the uniform contour's for its fewer triangles (bench/README.md, the adaptive octree
    // and the unfolding step; its GLB there: 0 self-intersections since the simplifier's and
    // the unfolding's fixes).
    bool adaptive = false;
    // A part whose leaves are all polyhedra (boxes, $fn-faceted cylinders and spheres,
    // polyhedron(), imported meshes) gets its exact boundary (PolyhedralBoundary.h) instead of
    // the grid's approximation; off only to measure the grid on such parts.
    bool exactPolyhedra = true;
    // Measure an all-polyhedral part's exact boundary both ways like any mesh. It is the part
    // by construction (and checked to be a closed manifold), so the figures only confirm
    // rounding; off, they are not computed (TessellateResult::measured is false). The CLI's
    // `export --check` turns it on.
    bool measureExact = true;
    // A part with curved leaves: when given, the same part with its curves faceted so that no
    // face stands more than `deviation` (world units) off them, all polyhedra, fitted as `fit`
    // says; or nothing when some leaf stays curved. tessellate() then writes that part's exact
    // boundary when it measures within the tolerance of the exact part (balanced first; a miss
    // is tried finer, or inscribed where the balanced fit kept material the part lacks), before
    // it takes the grid. The CLI facets with io/ChordFaceting.h.
    CurveFaceter facetCurves{};
    bool simplify = true;  // coarsen flat regions after the grid passes (Simplify.h)
    // Grid meshes larger than this are not simplified (0: no limit). Decimation (in slabs on
    // all workers, then once over the whole) and its re-measurement both ways cost more than
    // the grid passes on big meshes: csg_grid3 at T = 0.028, over the limit with or without the
    // octree, exports simplified in several times the grid mesh's time (bench/README.md,
    // csg_grid3 against OpenSCAD at OpenSCAD's own faceting error).
    // `csgray export --simplify` lifts the limit.
    uint64_t simplifyMaxTriangles = 1'000'000;
    int threads = 0;  // 0: all cores
    // The processes of a job (csg/mesh/Distribute.h) that cast the grid's rows and measure the
    // meshes with this one; null: this process alone. The mesh is the same either way.
    const ItemDistributor* distribute = nullptr;
};

// What one grid pass of tessellate() measured.
struct TessellatePass {
    double cellSize = 0.0;
    uint64_t cells = 0;
    uint64_t thinPlanes = 0;
    uint64_t triangles = 0;
    DualContourStats contour;  // the pass's contouring: active cells, the octree's blocks
    double error = 0.0;        // mesh to surface, max
    double backError = 0.0;    // surface to mesh, max
    double seconds = 0.0;      // wall time of the pass (grid, contouring, measuring)
    // Wall time of its phases (they add up to seconds): the Hermite casts, thin-feature rounds
    // included; dual contouring; mesh to surface; the BVH over the mesh; surface to mesh.
    double castSeconds = 0.0, contourSeconds = 0.0, toSurfaceSeconds = 0.0, bvhSeconds = 0.0,
           backSeconds = 0.0;
};

struct TessellateResult {
    TriangleMesh mesh;
    double tolerance = 0.0;  // the tolerance asked for (resolved when <= 0 was given)
    double cellSize = 0.0;   // h of the last pass (cells through thin features are thinner)
    uint64_t cells = 0;      // cells of the last pass, thin-feature planes included
    ThinPlanes thinPlanes;   // of the last pass
    int passes = 0;
    uint64_t rays = 0;        // Hermite rays of all passes (distance probes not counted)
    DistanceStats error;      // mesh to surface of the result, as measured
    DistanceStats backError;  // surface to mesh (kSurfaceRaysPerAxis^2 lines per axis)
    DualContourStats contour;
    bool toleranceMet = false;  // error.max and backError.max <= tolerance
    bool measured = true;       // false: an exact boundary not measured (measureExact)
    bool exact = false;         // the exact boundary of an all-polyhedral part
    // The deviation the curves were faceted to when the mesh is the exact boundary of the part
    // faceted by TessellateOptions::facetCurves (exact is then true too); 0 otherwise.
    double facetDeviation = 0.0;
    FacetFit facetFit = FacetFit::Inscribed;  // how those faceted curves sat on the exact ones
    double facetOneWayShare = 1.0;            // and the one-way leaves' share of the deviation
    PolyhedralBoundaryStats polyhedral;       // how it was made, or why it was declined
    bool capped = false;                      // maxCells stopped the refinement
    bool stalled = false;                 // refinement stopped paying (see Tessellate.h's header)
    uint64_t gridTriangles = 0;           // triangles of the grid's mesh, before simplification
    bool simplified = false;              // the simplified mesh was kept
    bool simplifySkipped = false;         // the grid's mesh was over simplifyMaxTriangles
    std::vector<TessellatePass> history;  // every grid pass, in order
};

// Throws std::invalid_argument for an unbounded scene (a bare half-space). An empty scene
// gives an empty mesh with toleranceMet = true.
TessellateResult tessellate(const Scene& scene, const TessellateOptions& options);

// The error budget of the first simplification try for a grid mesh measured as in `grid`
// (tolerance, error, backError): kMeshMeasureMargin T minus the worst measured error, at least
// kSimplifyMinBudget T, when the mesh is within the margin; else the flat-only pass's
// kSimplifyFlatBudget T. tessellate() uses it; exposed so benchmarks simplify as it does.
double firstSimplifyBudget(const TessellateResult& grid);

// One pass at a given spacing: grid (with thin-feature planes), Hermite data, contouring (with
// the octree when flatTolerance > 0, DualContourOptions). For tests and benchmarks.
TriangleMesh tessellateAt(const Scene& scene, double h, int threads, uint64_t* rays = nullptr,
                          DualContourStats* stats = nullptr, ThinPlanes* planes = nullptr,
                          double flatTolerance = 0.0);

}  // namespace csg
