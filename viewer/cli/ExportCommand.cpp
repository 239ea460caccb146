#include "viewer/cli/ExportCommand.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "csg/derived/Boundary2D.h"
#include "csg/mesh/Tessellate.h"
#include "io/ChordFaceting.h"
#include "io/DrawingFile.h"
#include "io/Evaluate.h"
#include "io/mesh/MeshFile.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/ExportFarm.h"
#include "viewer/cli/JobKey.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/cli/MeshOptions.h"

namespace viewer {

namespace {

// A measured distance: a sample that found no surface within the measure's reach (a mesh
// point far off the part) makes it infinite, which reads better as words than as "inf".
std::string distanceText(double d) {
    if (!std::isfinite(d)) return "out of reach (no surface near some mesh point)";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", d);
    return text;
}

// The help and the export summary state tol::kFlattenRel as "1e-7".
static_assert(csg::tol::kFlattenRel == 1e-7, "update \"1e-7\" in kExportHelp and exportDrawing");

const char* const kExportHelp =
    "usage: csgray export PART -o OUT.glb|OUT.gltf|OUT.obj|OUT.stl|OUT.3mf [options]\n"
    "       csgray export PART2D -o OUT.svg|OUT.dxf\n"
    "\n"
    "A 2-D part (its top level a 2-D shape, as OpenSCAD exports to SVG and DXF) is drawn\n"
    "as the boundary of its booleans, laid out as OpenSCAD lays its drawings out: lines,\n"
    "and circular arcs kept exact (SVG arc commands; DXF ARC and CIRCLE entities) where\n"
    "OpenSCAD writes chords; elliptic arcs and glyph curves become chords within 1e-7 of\n"
    "the shape's size. Coordinates are the shortest decimals that read back as the same\n"
    "doubles. --curves openscad draws OpenSCAD's own polygons. A 3-D part cannot be\n"
    "drawn (projection() makes a 2-D shape of it), nor a 2-D part meshed.\n"
    "\n"
    "A part whose every leaf is a polyhedron (cube, polyhedron(), an import, or a cylinder,\n"
    "sphere or straight-edged rotate_extrude faceted by $fn or --curves openscad) is a\n"
    "polyhedron itself: its mesh is its exact boundary, each leaf face cut where the others\n"
    "meet it and each piece kept when a ray along its normal says it bounds the part (--grid\n"
    "meshes it as below). A part whose other leaves are exact spheres, cylinders, tori,\n"
    "linear_extrudes and rotate_extrudes is meshed the same way after faceting them so that\n"
    "no face stands more than T/2 off the curve (each by its own radius; an extrusion\n"
    "becomes the prism or the revolution of its outline's chords, a twisted or unevenly\n"
    "scaled one as many slices and edge pieces as keep its curved sides within that, a torus\n"
    "the revolution of its tube's), kept when it measures within the tolerance of the exact\n"
    "part. Spheres, cylinders and a revolution's steps are faceted balanced (their corners\n"
    "as far outside the curve as their faces inside: fewer faces for the same distance), or\n"
    "inscribed where a balanced faceting keeps material the part lacks (a skin over a cut\n"
    "flush with a sphere's side; a balanced sphere stops at its poles' planes). A sphere and\n"
    "a cylinder of one radius that meet (the sphere's centre on the end of the cylinder's\n"
    "axis: a rounded box, a capsule) share one layout, so that their seam is clean. A\n"
    "faceting that misses is tried finer in proportion to its miss, up to three times; where\n"
    "leaves curved one way (cylinders) meet leaves curved both ways (spheres), one more try\n"
    "comes first, the one-way leaves alone at half the deviation (their faces are the\n"
    "cheaper ones). One that measures well within the tolerance is tried coarser by the\n"
    "margin it left, and again from each coarser one kept, up to three times. Every other\n"
    "part (algebraic surfaces, Bezier patches) is meshed from its own ray casts: rays along\n"
    "x, y and z through a grid (with planes added through walls and gaps thinner than a\n"
    "cell) give the exact surface crossings and normals on every grid edge; dual contouring\n"
    "with a QEF per cell keeps sharp edges and corners; the mesh is a closed,\n"
    "outward-oriented 2-manifold. The grid is refined until the measured distance between\n"
    "mesh and surface (both ways, sampled) is within the tolerance, or until a pass stops\n"
    "paying; then flat and gently curved regions are coarsened by edge collapses within what\n"
    "is left of the tolerance, and measured again (skipped when nothing is left).\n"
    "Normals are split along creases sharper than 40 degrees (box edges shade flat, curved\n"
    "faces smooth). GLB/glTF: one primitive per material, Y-up (the Z-up part is rotated at\n"
    "the root node). STL: binary unless --ascii, one facet per triangle. 3MF: one object in\n"
    "millimetres, the part's colours as base materials. Every format holds the same float\n"
    "vertices. The file is written atomically; an empty part gives an empty file and\n"
    "a warning. A one-line summary goes to stderr. Each loop that casts rays (the grid's\n"
    "rows, the measuring both ways, the exact boundary's faces) that runs longer than a\n"
    "moment shows its progress: a bar on a terminal, else a line every 5 seconds\n"
    "(CSGRAY_PROGRESS_SECONDS sets how many); --quiet hides it.\n"
    "Under mpirun the loops that cast rays (the grid's rows, the samples measuring each\n"
    "mesh, the exact boundary's faces) are spread over the ranks and rank 0 writes the\n"
    "file: the bytes one process writes (README.md, MPI).\n"
    "\n"
    "options:\n"
    "  -o FILE            the mesh file; the format follows the extension\n"
    "  --ascii            STL as text (default: binary)\n"
    "  --tolerance T      largest mesh-surface distance in part units (default: 1/500 of\n"
    "                     the bounding box diagonal)\n"
    "  --max-cells N      cap on the grid's cells (default 16777216); when it binds, the\n"
    "                     mesh is written with a warning and the error reached\n"
    "  --octree           blocks of up to 16^3 cells the surface crosses flat get one\n"
    "                     vertex each: ~45 % fewer triangles, ~1.4x the time (blocks\n"
    "                     whose triangles would fold are split and the contour redone)\n"
    "  --no-octree        one vertex per cell everywhere (the default)\n"
    "  --grid             mesh every part on the grid, polyhedral or faceted ones too\n"
    "  --check            measure an all-polyhedral part's exact boundary both ways too\n"
    "                     (by default it is not: it is the part, and checked closed)\n"
    "  --no-simplify      keep the grid's mesh (no coarsening of flat regions)\n"
    "  --simplify         coarsen even a grid mesh over a million triangles (skipped by\n"
    "                     default: there it takes longer than the meshing, e.g. 2.7x)\n"
    "  --threads N        worker threads (default: all cores)\n"
    "  --resume           keep the results of the loops that cast rays in OUT.journal as\n"
    "                     they finish; a job killed midway (a rank that died) and started\n"
    "                     again with the same part and options computes only what is\n"
    "                     missing, and writes the same bytes. The journal is removed once\n"
    "                     the mesh is written\n"
    "  --quiet            no summary on stderr\n"
    "  --verbose          also one line per grid pass (or on the exact boundary's\n"
    "                     pieces and phases) on stderr\n";

// A 2-D part drawn to SVG or DXF (the help above).
int exportDrawing(const CommonOptions& common, Report& report, const LoadedPart& part,
                  const std::string& output, bool quiet) {
    const io::Model& model = part.model;
    if (model.root && !model.twoD) {
        report.add(io::diagnosticAt(model, model.root->tags.source, io::Severity::Error,
                                    "export: the top level object is not a 2-D object, as "
                                    "OpenSCAD says: SVG and DXF hold drawings (projection() "
                                    "makes a 2-D shape of a solid)"));
        return kExitBadModel;
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<csg::Contour2D> contours;
    bool approximated = false;
    if (model.shape2D) {
        const csg::Boundary2D boundary = csg::boundaryOf(csg::Region2D(*model.shape2D));
        approximated = boundary.approximated;
        std::optional<std::vector<csg::Contour2D>> chained = csg::contoursOf(boundary);
        if (!chained) {
            report.add({common.part, 0, 0, io::Severity::Error,
                        "cannot draw: the shape's boundary does not close into contours"});
            return kExitBadModel;
        }
        contours = std::move(*chained);
    }
    if (contours.empty())
        report.add({common.part, 0, 0, io::Severity::Warning,
                    "the shape is empty (it has no area): wrote an empty drawing"});
    if (auto error = io::writeDrawing(output, contours)) {
        report.error(output, *error);
        return kExitIo;
    }
    size_t lines = 0, arcs = 0;
    for (const csg::Contour2D& contour : contours)
        for (const csg::BoundaryPiece& p : contour)
            ++(p.kind == csg::BoundaryPiece::Kind::Line ? lines : arcs);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto count = [](size_t n, const char* what) {
        return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    if (!quiet)
        std::fprintf(stderr, "csgray: export: %s: %s: %s and %s%s, %.2f s\n", output.c_str(),
                     count(contours.size(), "contour").c_str(), count(lines, "line").c_str(),
                     count(arcs, "circular arc").c_str(),
                     approximated ? " (elliptic arcs and curves as chords within 1e-7 of the "
                                    "shape's size)"
                                  : "",
                     seconds);
    return kExitOk;
}

// What decides the results of an export's loops beyond the part (JobKey.h): the options of
// the meshing. The format and --ascii only write them, --threads and ranks only share the work.
std::string exportKey(const CommonOptions& common, const csg::TessellateOptions& o) {
    char line[160];
    std::snprintf(line, sizeof line, "%a %llu %d %d %d %d %d %llu", o.tolerance,
                  (unsigned long long)o.maxCells, o.maxPasses, int(o.adaptive),
                  int(o.exactPolyhedra), int(o.measureExact), int(o.simplify),
                  (unsigned long long)o.simplifyMaxTriangles);
    return jobKey("export", common, line);
}

}  // namespace

int exportCommand(std::span<const std::string> args) {
    CommonOptions common;
    std::string output;
    csg::TessellateOptions options;
    options.measureExact = false;  // --check
    io::MeshWriteOptions writeOptions;
    bool quiet = false, verbose = false, resume = false;
    ArgCursor cursor(args);
    while (!cursor.done()) {
        if (auto o = cursor.option("-o")) {
            output = *o;
        } else if (auto t = cursor.option("--tolerance")) {
            options.tolerance = parsePositiveNumber(*t, "--tolerance");
        } else if (auto n = cursor.option("--max-cells")) {
            options.maxCells = uint64_t(parsePositiveNumber(*n, "--max-cells"));
        } else if (auto th = cursor.option("--threads")) {
            options.threads = parsePositiveInt(*th, "--threads", 1024);
        } else if (cursor.flag("--no-octree")) {
            options.adaptive = false;
        } else if (cursor.flag("--octree")) {
            options.adaptive = true;
        } else if (cursor.flag("--ascii")) {
            writeOptions.asciiStl = true;
        } else if (cursor.flag("--grid")) {
            options.exactPolyhedra = false;
        } else if (cursor.flag("--check")) {
            options.measureExact = true;
        } else if (cursor.flag("--no-simplify")) {
            options.simplify = false;
        } else if (cursor.flag("--simplify")) {
            options.simplifyMaxTriangles = 0;
        } else if (cursor.flag("--resume")) {
            resume = true;
        } else if (cursor.flag("--quiet")) {
            quiet = true;
        } else if (cursor.flag("--verbose")) {
            verbose = true;
        } else if (!cursor.common(common)) {
            throw UsageError("export: unknown option '" + cursor.peek() + "'");
        }
    }
    const dist::Ranks& ranks = dist::Ranks::job();
    if (common.help) {
        if (!ranks.root()) return kExitOk;  // under mpirun: once, by rank 0
        std::fputs(kExportHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    requirePart(common, "export");
    if (output.empty())
        throw UsageError(
            "export: -o OUT.glb|OUT.gltf|OUT.obj|OUT.stl|OUT.3mf (or OUT.svg|OUT.dxf) is "
            "required");
    const io::MeshFormat format = io::meshFormatOf(output);
    const bool drawing = io::drawingFormatOf(output) != io::DrawingFormat::Unknown;
    if (!drawing && (format == io::MeshFormat::Unknown || format == io::MeshFormat::Off))
        throw UsageError("export: cannot tell the format of '" + output +
                         "' (use .glb, .gltf, .obj, .stl or .3mf; .svg or .dxf for a 2-D part)");
    if (writeOptions.asciiStl && format != io::MeshFormat::Stl)
        throw UsageError("export: --ascii applies to .stl output only");

    // Under mpirun every rank loads the part and meshes it, the loops that cast rays spread
    // over the ranks (ExportFarm.h); rank 0 writes the file.
    Report report(common.jsonDiagnostics);
    LoadedPart part;
    const int loaded = loadPart(common, report, part);
    if (!ranks.allOk(loaded == kExitOk)) {
        if (loaded == kExitOk && ranks.root())
            report.error(common.part, "another rank cannot load it");
        return loaded != kExitOk ? loaded : kExitBadModel;
    }
    if (drawing) return ranks.root() ? exportDrawing(common, report, part, output, quiet) : kExitOk;
    if (const int code = requireSolids(part, report, "export"); code != kExitOk) return code;

    // Mesh the part: curved leaves faceted to a share of the tolerance first (io/ChordFaceting.h).
    options.facetCurves = io::curveFaceter(part.model.root);
    ExportJournal journal;
    if (resume && ranks.root())
        if (const std::string error =
                journal.open(dist::journalPathFor(output), exportKey(common, options));
            !error.empty()) {
            report.error(dist::journalPathFor(output).string(), error);
            report.finish();
            ranks.abort(kExitIo);
        }
    // Progress (rank 0's): the loops then go through the farm, which counts their items, also
    // when this process is alone (at no cost measured: bench/README.md, export --resume).
    const bool showProgress = !quiet && ranks.root();
    render::ProgressMeter progress(render::ProgressMeter::styleFor(!showProgress), "export");
    csg::ItemDistributor onRanks;
    if (resume || showProgress || (ranks.mpi() && ranks.size() > 1)) {
        onRanks = itemsOnRanks(ranks, csg::resolveThreads(options.threads), report,
                               resume && ranks.root() ? &journal : nullptr,
                               showProgress ? &progress : nullptr);
        options.distribute = &onRanks;
    }
    const auto start = std::chrono::steady_clock::now();
    csg::TessellateResult result;
    try {
        result = csg::tessellate(part.scene, options);
    } catch (const std::invalid_argument& e) {
        report.add(
            {common.part, 0, 0, io::Severity::Error, std::string("cannot mesh: ") + e.what()});
        return kExitBadModel;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!ranks.root()) return kExitOk;
    if (result.mesh.empty())
        report.add({common.part, 0, 0, io::Severity::Warning,
                    "the part is empty (nothing is left after its differences): wrote an empty "
                    "mesh"});
    else if (!result.toleranceMet)
        report.add({common.part, 0, 0, io::Severity::Warning,
                    "tolerance " + std::to_string(result.tolerance) + " not reached" +
                        (result.capped ? " within --max-cells" : "") +
                        (result.stalled ? " (finer cells stopped reducing the error)" : "") +
                        ": measured " +
                        distanceText(std::max(result.error.max, result.backError.max))});
    // Thin gaps left fused are a surface-to-mesh error the export's sampling can miss: say so
    // even when its own measurement is within the tolerance.
    const bool thinLeft = result.thinPlanes.unresolved > 0;
    if (!result.mesh.empty() && (!result.toleranceMet || thinLeft) &&
        result.contour.thinEdges > 0) {
        // The likely cause, where the grid shows it: features thinner than a cell.
        const csg::Vec3 at = result.contour.thinAt;
        char where[160];
        std::snprintf(where, sizeof where, "%.6g, %.6g, %.6g", at.x, at.y, at.z);
        report.add({common.part, 0, 0, io::Severity::Warning,
                    std::to_string(result.contour.thinEdges) +
                        " grid edges cross a wall or gap thinner than the cell (" +
                        std::to_string(result.cellSize) + "), e.g. near (" + where +
                        "): the mesh fuses or drops them there" +
                        (thinLeft ? " (" + std::to_string(result.thinPlanes.unresolved) +
                                        " between facing surfaces after " +
                                        std::to_string(result.thinPlanes.added) +
                                        " grid planes; `csgray compare` measures what that costs)"
                                  : std::string())});
    }

    // Write it.
    const auto writeStart = std::chrono::steady_clock::now();
    if (auto error = io::writeMesh(output, result.mesh, part.model.materials, writeOptions)) {
        report.error(output, *error);
        return kExitIo;
    }
    if (resume) {
        if (verbose && !quiet)
            std::fprintf(stderr, "csgray: export: --resume: %llu results taken from %s\n",
                         (unsigned long long)journal.reused(), journal.path().c_str());
        journal.remove();
    }
    const double writeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - writeStart).count();
    if (verbose && !quiet)
        for (const csg::TessellatePass& p : result.history)
            std::fprintf(
                stderr,
                "csgray: export: pass: cell %.6g, %llu cells (%llu thin-feature planes), "
                "%llu triangles (octree: %llu of %llu active cells in %llu blocks, %d round(s)%s), "
                "mesh->surface %s, surface->mesh %s, %.2f s (cast "
                "%.2f, contour %.2f, mesh->surface %.2f, bvh %.2f, surface->mesh %.2f)\n",
                p.cellSize, (unsigned long long)p.cells, (unsigned long long)p.thinPlanes,
                (unsigned long long)p.triangles, (unsigned long long)p.contour.octreeCells,
                (unsigned long long)p.contour.activeCells,
                (unsigned long long)p.contour.octreeLeaves, p.contour.octreeRounds,
                p.contour.octreeFallback ? ", not a manifold: uniform used" : "",
                distanceText(p.error).c_str(), distanceText(p.backError).c_str(), p.seconds,
                p.castSeconds, p.contourSeconds, p.toSurfaceSeconds, p.bvhSeconds, p.backSeconds);
    const csg::PolyhedralBoundaryStats& exact = result.polyhedral;
    if (verbose && !quiet && (result.exact || exact.declined))
        std::fprintf(stderr,
                     "csgray: export: exact polyhedral boundary: %s; %llu faces cut into %llu "
                     "pieces, %llu on the boundary, %llu T-junctions closed, %llu triangles "
                     "before merging, merged by %s; %.2f s cutting and classifying, %.2f s "
                     "assembling, %.2f s merging, %.2f s measuring\n",
                     result.exact ? "made" : exact.declined, (unsigned long long)exact.faces,
                     (unsigned long long)exact.pieces, (unsigned long long)exact.kept,
                     (unsigned long long)exact.tJunctions,
                     (unsigned long long)exact.trianglesBeforeMerge, exact.mergedBy,
                     exact.classifySeconds, exact.assembleSeconds, exact.mergeSeconds,
                     exact.measureSeconds);
    if (verbose && !quiet)
        std::fprintf(stderr, "csgray: export: writing %s (checks, crease normals) took %.2f s\n",
                     output.c_str(), writeSeconds);
    char faceted[160] = "", oneWay[64] = "";
    if (result.facetOneWayShare < 1.0)
        std::snprintf(oneWay, sizeof oneWay, " (those curved one way within %.3g)",
                      result.facetOneWayShare * result.facetDeviation);
    if (result.facetDeviation > 0.0)
        std::snprintf(faceted, sizeof faceted,
                      " of the part with its curves faceted within %.3g%s, %s",
                      result.facetDeviation, oneWay,
                      result.facetFit == csg::FacetFit::Balanced ? "balanced" : "inscribed");
    if (!quiet && result.exact && !result.measured)
        std::fprintf(stderr,
                     "csgray: export: %s: %zu triangles (the exact polyhedral boundary), %zu "
                     "vertices, not measured (the part's own boundary: --check or compare "
                     "measures it), %.2f s\n",
                     output.c_str(), result.mesh.triangles.size(), result.mesh.positions.size(),
                     seconds);
    else if (!quiet && result.exact)
        std::fprintf(stderr,
                     "csgray: export: %s: %zu triangles (the exact polyhedral boundary%s), %zu "
                     "vertices, mesh->surface %s, surface->mesh %s (tolerance %.3g), %.2f s\n",
                     output.c_str(), result.mesh.triangles.size(), faceted,
                     result.mesh.positions.size(), distanceText(result.error.max).c_str(),
                     distanceText(result.backError.max).c_str(), result.tolerance, seconds);
    else if (!quiet)
        std::fprintf(
            stderr,
            "csgray: export: %s: %zu triangles (grid %llu%s), %zu vertices, cell %.6g, "
            "%d pass(es), mesh->surface %s, surface->mesh %s (tolerance %.3g), "
            "%.2f s\n",
            output.c_str(), result.mesh.triangles.size(), (unsigned long long)result.gridTriangles,
            result.simplified        ? ", simplified"
            : result.simplifySkipped ? ", not simplified: over a million, --simplify forces it"
                                     : "",
            result.mesh.positions.size(), result.cellSize, result.passes,
            distanceText(result.error.max).c_str(), distanceText(result.backError.max).c_str(),
            result.tolerance, seconds);
    return kExitOk;
}

}  // namespace viewer
