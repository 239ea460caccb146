#include "csg/mesh/Tessellate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "csg/mesh/HermiteGrid.h"
#include "csg/mesh/Simplify.h"
#include "primitives/base/Tolerances.h"

namespace csg {

TriangleMesh tessellateAt(const Scene& scene, double h, int threads, uint64_t* rays,
                          DualContourStats* stats, ThinPlanes* planes, double flatTolerance) {
    const Bounds3 box = scene.bounds();
    if (box.empty()) return {};
    const HermiteGrid grid = castResolvingThinFeatures(scene, box, h, threads, rays, planes);
    DualContourOptions contour;
    contour.threads = threads;
    contour.flatTolerance = flatTolerance;
    return dualContour(grid, contour, stats);
}

namespace {

// The worst measured error of the grid's mesh that a simplification budget is drawn from. An
// unresolved surface-to-mesh sample (+inf: a gap the grid fused, HermiteGrid::thinEdges) is not
// a budget the collapses could spend; the finite figures are.
double worstMeasured(const TessellateResult& grid) {
    const double finiteBack = std::isfinite(grid.backError.max) ? grid.backError.max : 0.0;
    return std::max(grid.error.max, finiteBack);
}

}  // namespace

double firstSimplifyBudget(const TessellateResult& grid) {
    const double target = tol::kMeshMeasureMargin * grid.tolerance;
    const double worst = worstMeasured(grid);
    return worst <= target ? std::max(target - worst, tol::kSimplifyMinBudget * grid.tolerance)
                           : tol::kSimplifyFlatBudget * grid.tolerance;
}

namespace {

// The simplification step of tessellate() (see Tessellate.h); result holds the grid's mesh and
// its measurements, and keeps them unless a simplified mesh measures within bounds.
void simplifyWithinBudget(const Scene& scene, TessellateResult& result,
                          const DistanceOptions& measure) {
    const double target = tol::kMeshMeasureMargin * result.tolerance;
    const double worst = worstMeasured(result);
    // A grid mesh over the margin leaves only the flat-only pass. When refinement gave up on
    // the margin (the cell cap, or a stall at thin gaps), that mesh is the largest the part
    // gets and on csg_grid3 the pass cost more than the whole export for a modest cut in
    // triangles: it cannot pay there, and the grid's mesh is kept. Otherwise (maxPasses ran
    // out, typically at a coarse tolerance) it can: bracket's flat faces collapse to a small
    // fraction of its grid triangles (bench/README.md, mesh export vs OpenSCAD and the
    // tolerance sweeps).
    if (worst > target && (result.capped || result.stalled)) return;
    // Each try: its budget, and the bound its measurements are held to (the flat-only pass
    // leaves the surface where it was, so it is held to T, not to the margin).
    struct Try {
        double budget, bound;
    };
    std::vector<Try> tries;
    if (worst <= target) tries.push_back({firstSimplifyBudget(result), target});
    tries.push_back({tol::kSimplifyFlatBudget * result.tolerance, result.tolerance});
    for (const auto [budget, bound] : tries) {
        const double allowedTo = std::max(bound, result.error.max);
        const double allowedBack = std::max(bound, result.backError.max);
        TriangleMesh coarse = simplify(result.mesh, budget, nullptr, measure.threads);
        if (coarse.triangles.size() == result.mesh.triangles.size()) return;
        const DistanceStats to = meshToSurface(scene, coarse, measure);
        if (!(to.max <= allowedTo)) continue;
        const TriangleBvh bvh(coarse, measure.threads);
        const DistanceStats back = surfaceToMesh(scene, bvh, kSurfaceRaysPerAxis, measure);
        if (!(back.max <= allowedBack)) continue;
        result.mesh = std::move(coarse);
        result.error = to;
        result.backError = back;
        result.toleranceMet = std::max(to.max, back.max) <= result.tolerance;
        result.simplified = true;
        return;
    }
}

// The factor h shrinks by after a pass whose worst errors (mesh to surface, surface to mesh)
// missed target, with a 0.85 safety factor. Mesh to surface: linear, not quadratic: its worst
// errors sit at creases (a QEF vertex clamped to its cell) and shrink only in proportion to h.
// Surface to mesh, once every mesh point is within target: what is left is surface the mesh
// does not reach, a chord's sagitta over curved faces (quadratic in h) or a gap or edge the grid
// fused, which falls in steps as planes and cells resolve it rather than in proportion to h; the
// linear law there overshot (csg_grid3, T = 0.029: 0.022 / 0.048 at h = 0.0397 led to h = 0.0162
// with 0.0116 / 0.0072, while h = 0.0239 gives 0.0177 / 0.0091 at half the triangles). One pass
// too coarse costs a pass at the cost of the one before; one too fine costs 1 / step^2. The
// step is at least 0.15 (a pass costs ~1 / step^2 = 44x the one before at most; a pass's cost
// grows with its triangles, ~1 / h^2): the linear law from the first, coarse pass is trusted
// that far, and on csg_grid3 it lands within T in one step (T = 0.029: 0.152 at h = 0.159 gives
// h = 0.0238, 0.0131 / 0.0100), where 0.25 spent a whole pass at h = 0.0397 on the way. A
// non-finite error (a sample saw no surface within reach) says nothing of the scale: 0.25.
double refinementStep(double toSurface, double toMesh, double target) {
    double step = 1.0;
    if (!std::isfinite(toSurface) || !std::isfinite(toMesh)) return 0.25;
    if (toSurface > target) step = std::min(step, 0.85 * target / toSurface);
    if (toMesh > target)
        step = std::min(
            step, toSurface > target ? 0.85 * target / toMesh : 0.85 * std::sqrt(target / toMesh));
    return std::clamp(step, 0.15, 0.85);
}

}  // namespace

TessellateResult tessellate(const Scene& scene, const TessellateOptions& options) {
    TessellateResult result;
    const Bounds3 box = scene.bounds();
    if (box.empty()) {
        result.toleranceMet = true;
        return result;
    }
    if (!box.finite()) throw std::invalid_argument("the part is unbounded (a bare half-space?)");

    // Step 1: the tolerance, and the spacing below which the cell cap would be exceeded.
    const double diagonal = glm::length(box.extent());
    const double tolerance = options.tolerance > 0.0 ? options.tolerance : diagonal / 500.0;
    result.tolerance = tolerance;
    auto cellsAt = [&](double h) { return makeGrid(box, h).cellCount(); };
    double hMin = diagonal / 4.0;
    while (cellsAt(hMin) < options.maxCells && hMin > diagonal * 1e-7) hMin *= 0.5;
    // Bisect to the smallest h within the cap (the count is monotone in h up to rounding).
    for (double lo = hMin, hi = 2.0 * hMin, i = 0; i < 20; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (cellsAt(mid) > options.maxCells)
            lo = mid;
        else
            hi = mid;
        hMin = hi;
    }

    // An all-polyhedral part: its exact boundary, measured both ways like the grid's mesh.
    DistanceOptions measure;
    measure.threads = options.threads;
    measure.goodEnough = tolerance;
    measure.distribute = options.distribute;
    // Measures a mesh of the exact boundary both ways into result (the figures are upper
    // bounds, tight to rounding on an exact mesh: MeshDistance.h samples off its edges): mesh
    // to surface (reach: how far a sample looks for the surface; farther is +inf, unresolved),
    // returning its maximum, then surface to mesh, returning the larger maximum.
    const auto measureToSurface = [&](const TriangleMesh& mesh, double reach) {
        measure.reach = reach;
        const auto start = std::chrono::steady_clock::now();
        result.error = meshToSurface(scene, mesh, measure);
        result.backError = {};
        result.polyhedral.measureSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return result.error.max;
    };
    const auto measureToMesh = [&](const TriangleMesh& mesh) {
        const auto start = std::chrono::steady_clock::now();
        const TriangleBvh bvh(mesh, options.threads);
        result.backError = surfaceToMesh(scene, bvh, kSurfaceRaysPerAxis, measure);
        result.polyhedral.measureSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return std::max(result.error.max, result.backError.max);
    };
    if (options.exactPolyhedra && allLeavesPolyhedral(scene)) {
        if (auto mesh = polyhedralBoundary(scene, options.threads, &result.polyhedral,
                                           options.distribute)) {
            result.mesh = std::move(*mesh);
            result.exact = true;
            result.gridTriangles = result.mesh.triangles.size();
            if (!options.measureExact) {
                result.measured = false;
                result.toleranceMet = true;
                return result;
            }
            measureToSurface(result.mesh, tolerance);
            result.toleranceMet = measureToMesh(result.mesh) <= tolerance;
            return result;
        }
    }

    // A part with curved leaves faceted within a share of the tolerance: the exact boundary of
    // that polyhedron, kept when it measures within the margin against the exact part. The
    // balanced fit first (about 1 / sqrt(2) of the fragments per curved direction). A miss
    // far beyond the deviation is material the exact part lacks (a balanced sphere's skin over
    // a cut flush with its side), which no finer balanced fit removes: then the inscribed fit at
    // the same deviation. Any other miss (curves meeting at a rim move it by up to about twice the
    // deviation) is tried again finer: first the leaves curved one way only, where they meet
    // leaves curved both ways (CurveFaceter::mixedCurvature), then all, in proportion to how far it
    // missed.
    if (options.exactPolyhedra && options.facetCurves) {
        const double margin = tol::kMeshMeasureMargin * tolerance;
        double deviation = tol::kFacetDeviationFraction * tolerance;
        FacetFit fit = FacetFit::Balanced;
        double oneWayShare = 1.0;
        // The exact boundary of the part faceted so; nothing when a leaf stays curved or the
        // boundary does not close.
        const auto facetedBoundary = [&](double d) -> std::optional<TriangleMesh> {
            const std::optional<Scene> faceted = options.facetCurves(d, fit, oneWayShare);
            if (!faceted) return std::nullopt;
            return polyhedralBoundary(*faceted, options.threads, &result.polyhedral,
                                      options.distribute);
        };
        // The measured distance of a faceting within the margin sits near its deviation, often
        // well under the margin: a coarser faceting, the deviation scaled from `measured` up
        // to the slack, kept with its figures when it has fewer than `triangles` triangles and
        // measures within the margin both ways (then `measured` and `triangles` are its own).
        const auto coarserKept = [&](double& measured, size_t& triangles) {
            const double coarser =
                deviation * std::min(tol::kFacetSlackMaxGain,
                                     tol::kFacetSlackTarget * margin / std::max(measured, 1e-300));
            if (coarser < tol::kFacetSlackMinGain * deviation) return false;
            // The figures the attempt overwrites, restored when it is not kept.
            const DistanceStats error = result.error, backError = result.backError;
            const PolyhedralBoundaryStats stats = result.polyhedral;
            std::optional<TriangleMesh> mesh = facetedBoundary(coarser);
            if (mesh && mesh->triangles.size() < triangles) {
                const double toSurface = measureToSurface(*mesh, tolerance);
                const double toMesh = toSurface <= margin ? measureToMesh(*mesh) : kInfinity;
                if (toMesh <= margin) {
                    measured = std::max(toSurface, toMesh);
                    triangles = mesh->triangles.size();
                    result.mesh = std::move(*mesh);
                    deviation = coarser;
                    return true;
                }
            }
            result.error = error;
            result.backError = backError;
            result.polyhedral = stats;
            return false;
        };
        // The one-way leaves' finer try is an attempt beside kFacetAttempts.
        const bool mixed = options.facetCurves.mixedCurvature;
        const int attempts = tol::kFacetAttempts + (mixed ? 1 : 0);
        for (int attempt = 0; attempt <= attempts; ++attempt) {
            std::optional<TriangleMesh> mesh = facetedBoundary(deviation);
            if (!mesh) break;
            // Far enough to tell a miss of the faceting (up to kFacetSkinFactor times the
            // deviation) from material the part lacks.
            const double reach = std::max(tolerance, tol::kFacetSkinFactor * deviation);
            double measured = measureToSurface(*mesh, reach);
            // Within the margin one way, the slack first: when a coarser faceting is kept,
            // this one need not be measured the other way (the costlier way on small meshes).
            bool keptCoarser = false;
            if (measured <= margin) {
                size_t triangles = mesh->triangles.size();
                for (int k = 0; k < tol::kFacetSlackAttempts && coarserKept(measured, triangles);
                     ++k)
                    keptCoarser = true;
                if (!keptCoarser) measured = measureToMesh(*mesh);
            }
            if (measured > margin) {
                result.polyhedral.declined =
                    "the faceted part did not measure within the tolerance";
                if (fit == FacetFit::Balanced && !(measured <= tol::kFacetSkinFactor * deviation))
                    fit = FacetFit::Inscribed;
                else if (mixed && oneWayShare == 1.0)
                    oneWayShare = tol::kFacetOneWayShare;
                else
                    deviation *= std::clamp(tol::kFacetSlackTarget * margin / measured,
                                            tol::kFacetFinerMin, tol::kFacetFinerMax);
                continue;
            }
            if (!keptCoarser) result.mesh = std::move(*mesh);
            result.exact = true;
            result.facetDeviation = deviation;
            result.facetFit = fit;
            result.facetOneWayShare = oneWayShare;
            result.toleranceMet = true;
            result.gridTriangles = result.mesh.triangles.size();
            return result;
        }
        result.error = result.backError = {};
    }

    // Step 2: the first spacing from the curvature rule with the reference radius.
    const double radius = tol::kMeshReferenceRadius * diagonal;
    double h = std::min(std::sqrt(8.0 * radius * tolerance / 3.0), diagonal / 8.0);

    // Step 3: mesh, measure, refine.
    for (int pass = 0; pass < std::max(1, options.maxPasses); ++pass) {
        if (h <= hMin) {
            result.capped = h < hMin;
            h = hMin;
        }
        // Each phase timed on its own (TessellatePass), so the cost of a pass is visible.
        TessellatePass record;
        auto clock = std::chrono::steady_clock::now();
        const auto passStart = clock;
        auto lap = [&clock]() {
            const auto now = std::chrono::steady_clock::now();
            const double seconds = std::chrono::duration<double>(now - clock).count();
            clock = now;
            return seconds;
        };
        result.contour = {};
        result.thinPlanes = {};
        const HermiteGrid grid = castResolvingThinFeatures(
            scene, box, h, options.threads, &result.rays, &result.thinPlanes, options.distribute);
        record.castSeconds = lap();
        DualContourOptions contour;
        contour.threads = options.threads;
        contour.flatTolerance = options.adaptive ? tol::kOctreeFlatFraction * tolerance : 0.0;
        result.mesh = dualContour(grid, contour, &result.contour);
        record.contourSeconds = lap();
        result.cellSize = h;
        result.cells = result.contour.cells;
        result.passes = pass + 1;
        measure.reach = 2.0 * h;
        result.error = meshToSurface(scene, result.mesh, measure);
        record.toSurfaceSeconds = lap();
        const TriangleBvh bvh(result.mesh, options.threads);
        record.bvhSeconds = lap();
        result.backError = surfaceToMesh(scene, bvh, kSurfaceRaysPerAxis, measure);
        record.backSeconds = lap();
        const double worst = std::max(result.error.max, result.backError.max);
        result.toleranceMet = worst <= tolerance;
        record.cellSize = h;
        record.cells = result.cells;
        record.thinPlanes = result.thinPlanes.added;
        record.triangles = result.mesh.triangles.size();
        record.contour = result.contour;
        record.error = result.error.max;
        record.backError = result.backError.max;
        record.seconds = std::chrono::duration<double>(clock - passStart).count();
        result.history.push_back(record);
        // Refine until the sampled error is within a margin of T: samples miss the true
        // maximum by a little, and a different sampling (compare's) must agree.
        const double target = tol::kMeshMeasureMargin * tolerance;
        if (worst <= target || h <= hMin) break;
        // On a part with walls or gaps thinner than a cell, stop when the last refinement of a
        // pass that missed T bought less than tol::kMeshStallFraction of what the linear law
        // promised: the error then sits where finer cells do not reach (a wedge of a gap
        // narrower than any cell), and every further pass costs more than all before it.
        // Elsewhere a small gain is the sampled maximum's noise at creases: refining goes on.
        if (pass > 0 && result.thinPlanes.added > 0) {
            const TessellatePass& before = result.history[result.history.size() - 2];
            const double promised = 1.0 - h / before.cellSize;
            const double previous = std::max(before.error, before.backError);
            if (std::isfinite(previous) && previous > tolerance &&
                worst > previous * (1.0 - tol::kMeshStallFraction * promised)) {
                result.stalled = true;
                break;
            }
        }
        h *= refinementStep(result.error.max, result.backError.max, target);
    }
    result.gridTriangles = result.mesh.triangles.size();
    if (options.simplify && !result.mesh.empty()) {
        result.simplifySkipped =
            options.simplifyMaxTriangles > 0 && result.gridTriangles > options.simplifyMaxTriangles;
        if (!result.simplifySkipped) simplifyWithinBudget(scene, result, measure);
    }
    return result;
}

}  // namespace csg
