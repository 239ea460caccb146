#include "viewer/cli/CompareCommand.h"

#include <cmath>
#include <cstdio>

#include "csg/Volume.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/MeshDistance.h"
#include "csg/mesh/TriangleBvh.h"
#include "io/mesh/MeshFile.h"
#include "primitives/base/Json.h"
#include "primitives/base/Tolerances.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/cli/MeshOptions.h"

namespace viewer {

namespace {

// The help states the contact tolerance in words; a change of the constant must change it.
static_assert(csg::tol::kSelfIntersectionContactRel == 1e-6);
const char* const kCompareHelp =
    "usage: csgray compare PART MESH [options]\n"
    "\n"
    "Compares a mesh (OBJ, STL, OFF, 3MF, GLB or glTF) with the part's exact surface and prints "
    "the\n"
    "figures on stdout: mesh volume (divergence theorem) against the part's (span\n"
    "integration); the one-sided distances mesh->surface (every vertex, triangle centroid and\n"
    "edge midpoint, measured along lines through it: the mesh normal, the axes, the\n"
    "diagonals; an upper bound at each sample) and surface->mesh (exact surface points from\n"
    "a grid of rays along x, y and z, each at its Euclidean distance to the nearest triangle\n"
    "of the mesh); watertightness and orientation of the mesh, and its self-intersections\n"
    "(triangle pairs crossing other than where they share vertices; contacts within 1e-6 of\n"
    "the largest coordinate, a GLB's float rounding, do not count). The maxima are over the\n"
    "samples. glTF node transforms are applied, so a csgray GLB compares in the part's own\n"
    "Z-up frame.\n"
    "Exit 0 when both distances are within the tolerance and the mesh is closed, manifold\n"
    "and oriented outward; 1 when not (self-intersections are reported, not judged).\n"
    "\n"
    "options:\n"
    "  --tolerance T      the distance allowed (default: 1/500 of the part's bounding box\n"
    "                     diagonal)\n"
    "  --samples N        surface->mesh rays per axis and side (default 256: 3 N^2 rays)\n"
    "  --json             JSON on stdout instead of text\n"
    "  --threads N        worker threads (default: all cores)\n";

void writeDistance(csg::JsonWriter& json, const char* name, const csg::DistanceStats& d) {
    json.key(name).beginObject();
    json.key("max").value(d.max).key("mean").value(d.mean).key("samples").value(d.samples);
    json.key("unresolved").value(d.unresolved);
    json.key("worst").beginArray().value(d.worst.x).value(d.worst.y).value(d.worst.z).endArray();
    json.endObject();
}

}  // namespace

int compareCommand(std::span<const std::string> args) {
    CommonOptions common;
    std::string meshFile;
    double tolerance = 0.0;
    int samples = 256, threads = 0;
    bool json = false;
    ArgCursor cursor(args);
    while (!cursor.done()) {
        // The second positional argument is the mesh (common() takes the first, the part).
        if (!common.part.empty() && meshFile.empty() && !cursor.peek().starts_with("-")) {
            meshFile = cursor.take();
        } else if (auto t = cursor.option("--tolerance")) {
            tolerance = parsePositiveNumber(*t, "--tolerance");
        } else if (auto n = cursor.option("--samples")) {
            samples = parsePositiveInt(*n, "--samples", 8192);
        } else if (auto th = cursor.option("--threads")) {
            threads = parsePositiveInt(*th, "--threads", 1024);
        } else if (cursor.flag("--json")) {
            json = true;
        } else if (!cursor.common(common)) {
            throw UsageError("compare: unknown option '" + cursor.peek() + "'");
        }
    }
    if (common.help) {
        std::fputs(kCompareHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    requirePart(common, "compare");
    if (meshFile.empty()) throw UsageError("compare: the MESH file is required");
    if (io::meshFormatOf(meshFile) == io::MeshFormat::Unknown)
        throw UsageError("compare: cannot tell the format of '" + meshFile +
                         "' (use .obj, .stl, .off, .3mf, .glb or .gltf)");

    Report report(common.jsonDiagnostics);
    LoadedPart part;
    if (const int code = loadPart(common, report, part); code != kExitOk) return code;
    if (const int code = requireSolids(part, report, "compare"); code != kExitOk) return code;
    io::MeshReadResult read = io::readMesh(meshFile);
    if (!read.mesh) {
        report.add({meshFile, read.line, read.column, io::Severity::Error, read.error});
        return read.unreadable ? kExitIo : kExitBadModel;
    }
    const csg::TriangleMesh& mesh = *read.mesh;
    const csg::Bounds3 box = part.scene.bounds();
    if (!box.empty() && !box.finite()) {
        report.add(
            {common.part, 0, 0, io::Severity::Error, "cannot compare: the part is unbounded"});
        return kExitBadModel;
    }

    // Step 1: topology and volumes.
    const csg::MeshTopology topo = csg::checkTopology(mesh);
    const double meshVolume = csg::signedVolume(mesh);
    const double partVolume = csg::volume(part.scene, 1024, threads);
    const bool outward = meshVolume >= 0.0;
    const csg::TriangleBvh bvh(mesh, threads);
    const csg::SelfIntersections crossings =
        csg::findSelfIntersections(mesh, bvh, csg::tol::kSelfIntersectionContactRel, threads);

    // Step 2: distances, reaching well past the tolerance so a bad mesh shows its error.
    const double diagonal = box.empty() ? 0.0 : glm::length(box.extent());
    if (tolerance <= 0.0) tolerance = diagonal > 0.0 ? diagonal / 500.0 : 1e-3;
    csg::DistanceOptions options;
    options.threads = threads;
    options.goodEnough = tolerance;
    options.reach = std::max(10.0 * tolerance, diagonal / 50.0);
    const csg::DistanceStats toSurface = csg::meshToSurface(part.scene, mesh, options);
    const csg::DistanceStats toMesh = csg::surfaceToMesh(part.scene, bvh, samples, options);
    const bool within =
        toSurface.max <= tolerance && toMesh.max <= tolerance && topo.closedManifold() && outward;

    // Step 3: the report.
    std::string out;
    if (json) {
        csg::JsonWriter w(out);
        w.beginObject();
        w.key("part").value(common.part).key("mesh").value(meshFile);
        w.key("vertices").value(uint64_t(mesh.positions.size()));
        w.key("triangles").value(uint64_t(mesh.triangles.size()));
        w.key("volume").beginObject().key("mesh").value(meshVolume).key("part").value(partVolume);
        w.key("relativeDifference")
            .value(partVolume > 0.0 ? (meshVolume - partVolume) / partVolume : 0.0);
        w.endObject();
        w.key("topology").beginObject();
        w.key("closedManifold").value(topo.closedManifold()).key("outward").value(outward);
        w.key("edges").value(topo.edges).key("boundaryEdges").value(topo.boundaryEdges);
        w.key("nonManifoldEdges").value(topo.nonManifoldEdges);
        w.key("misorientedEdges").value(topo.misorientedEdges);
        w.key("nonManifoldVertices").value(topo.nonManifoldVertices);
        w.key("degenerateTriangles").value(topo.degenerateTriangles);
        w.key("selfIntersections").value(crossings.pairs);
        w.key("coplanarOverlaps").value(crossings.coplanarPairs);
        if (crossings.pairs > 0) {
            w.key("selfIntersectionAt").beginArray().value(crossings.example.x);
            w.value(crossings.example.y).value(crossings.example.z).endArray();
        }
        w.endObject();
        writeDistance(w, "meshToSurface", toSurface);
        writeDistance(w, "surfaceToMesh", toMesh);
        w.key("tolerance").value(tolerance).key("withinTolerance").value(within);
        w.endObject();
        out += '\n';
    } else {
        char line[512];
        auto add = [&](const char* fmt, auto... v) {
            std::snprintf(line, sizeof line, fmt, v...);
            out += line;
        };
        add("mesh            %s: %zu vertices, %zu triangles\n", meshFile.c_str(),
            mesh.positions.size(), mesh.triangles.size());
        add("volume          mesh %.9g, part %.9g (%+.3e relative)\n", meshVolume, partVolume,
            partVolume > 0.0 ? (meshVolume - partVolume) / partVolume : 0.0);
        add("topology        %s, %s (boundary edges %llu, non-manifold edges %llu, misoriented "
            "edges %llu, non-manifold vertices %llu, degenerate triangles %llu, "
            "self-intersections %llu, %llu of them coplanar overlaps)\n",
            topo.closedManifold() ? "closed manifold" : "NOT closed manifold",
            outward ? "outward" : "INWARD", (unsigned long long)topo.boundaryEdges,
            (unsigned long long)topo.nonManifoldEdges, (unsigned long long)topo.misorientedEdges,
            (unsigned long long)topo.nonManifoldVertices,
            (unsigned long long)topo.degenerateTriangles, (unsigned long long)crossings.pairs,
            (unsigned long long)crossings.coplanarPairs);
        if (crossings.pairs > 0)
            add("self-crossing   at %.9g, %.9g, %.9g (one of the %llu pairs)\n",
                crossings.example.x, crossings.example.y, crossings.example.z,
                (unsigned long long)crossings.pairs);
        add("mesh->surface   max %.6g, mean %.6g over %llu samples (%llu unresolved)\n",
            toSurface.max, toSurface.mean, (unsigned long long)toSurface.samples,
            (unsigned long long)toSurface.unresolved);
        add("surface->mesh   max %.6g, mean %.6g over %llu samples (%llu unresolved)\n", toMesh.max,
            toMesh.mean, (unsigned long long)toMesh.samples, (unsigned long long)toMesh.unresolved);
        add("tolerance       %.6g: %s\n", tolerance, within ? "within" : "NOT within");
    }
    if (!report.writeStdout(out)) return kExitIo;
    return within ? kExitOk : kExitBadModel;
}

}  // namespace viewer
