// What the mesh fuzzer (fuzz_mesh.cpp) and the mesh corpus replay (fuzz_replay mesh) do with
// one input: parse it as every mesh format compare reads, check the readers' promises, and run
// compare's mesh checks on any mesh that comes out; parse it as every format import() reads,
// build the mesh primitive from it and check that lines through its vertices cross a closed
// mesh an even number of times; read it as a DXF and as an SVG drawing (import()'s 2-D
// readers, exact and faceted) and check that every outline is finite and closed (lines through
// its segment ends cross it an even number of times). Any crash, hang, sanitizer report or
// abort() here is a bug.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string_view>

#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/TriangleBvh.h"
#include "io/DxfFile.h"
#include "io/SvgFile.h"
#include "io/mesh/MeshFile.h"
#include "primitives/Polyhedron.h"
#include "primitives/base/Tolerances.h"

namespace fuzz {

// A drawing's outline: finite, and closed: lines through (up to 16 of) its segments' starts,
// skew and along the axes, cross it an even number of times.
inline void checkDrawingOutline(const csg::Outline& outline) {
    for (const csg::Segment2& s : outline.segments)
        for (const csg::Vec2& p : s.p)
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) std::abort();
    std::vector<csg::Crossing2> crossings;
    const size_t step = std::max<size_t>(1, outline.segments.size() / 16);
    for (size_t i = 0; i < outline.segments.size(); i += step)
        for (const csg::Vec2 d : {csg::Vec2(0.3, -0.7), csg::Vec2(1, 0), csg::Vec2(0, 1)}) {
            crossings.clear();
            outline.crossings(outline.segments[i].start() - d, d, crossings);
            if (crossings.size() % 2 != 0) std::abort();
        }
}

inline void readMeshInput(std::string_view bytes) {
    using io::MeshFormat;
    for (const MeshFormat format : {MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Off,
                                    MeshFormat::ThreeMf, MeshFormat::Glb, MeshFormat::Gltf}) {
        // A directory that does not exist: a glTF's external buffers are not read from disk.
        const io::MeshReadResult r = io::parseMesh(bytes, format, "/nonexistent/csgray-fuzz");
        // A mesh exactly when there is no error; a column only with a line.
        if (r.mesh.has_value() == !r.error.empty()) std::abort();
        if (r.line == 0 && r.column != 0) std::abort();
        if (!r.mesh) continue;
        const csg::TriangleMesh& mesh = *r.mesh;
        for (const auto& triangle : mesh.triangles)
            for (const uint32_t corner : triangle)
                if (corner >= mesh.positions.size()) std::abort();
        for (const csg::Vec3& p : mesh.positions)
            for (int k = 0; k < 3; ++k)
                if (!(std::abs(p[k]) <= csg::tol::kMeshCoordinateMax)) std::abort();
        // compare's figures of the mesh alone: none may be NaN.
        (void)csg::checkTopology(mesh);
        if (!std::isfinite(csg::signedVolume(mesh))) std::abort();
        const csg::TriangleBvh bvh(mesh, 1);
        (void)csg::findSelfIntersections(mesh, bvh, csg::tol::kSelfIntersectionContactRel, 1);
        if (!mesh.positions.empty() &&
            std::isnan(bvh.distance(mesh.positions.front() + csg::Vec3(0.5, 0.25, 0.125),
                                    csg::tol::kMeshCoordinateMax)))
            std::abort();
    }
    for (const MeshFormat format :
         {MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Off, MeshFormat::ThreeMf}) {
        io::PolygonMeshReadResult r = io::parsePolygonMesh(bytes, format);
        if (r.mesh.has_value() == !r.error.empty()) std::abort();
        if (!r.mesh) continue;
        for (const uint32_t corner : r.mesh->faces.corners)
            if (corner >= r.mesh->positions.size()) std::abort();
        const csg::Polyhedron solid = csg::Polyhedron::make(r.mesh->positions, r.mesh->faces);
        if (solid.invalidReason()) continue;
        // Lines through (up to 64 of) the vertices, along a skew direction and along the axes.
        std::vector<csg::Polyhedron::Crossing> crossings;
        const size_t step = std::max<size_t>(1, solid.data->vertices.size() / 64);
        for (size_t v = 0; v < solid.data->vertices.size(); v += step)
            for (const csg::Vec3 d :
                 {csg::Vec3(0.3, -0.7, 0.6), csg::Vec3(0, 0, 1), csg::Vec3(1, 0, 0)}) {
                solid.crossings(solid.data->vertices[v] - d, d, crossings);
                if (solid.edges().closed() && crossings.size() % 2 != 0) std::abort();
                csg::LocalSpans spans;
                solid.spans(solid.data->vertices[v] - d, d, spans);
            }
    }
    for (const bool faceted : {false, true}) {
        io::DxfOptions dxfOptions;
        dxfOptions.faceted = faceted;
        dxfOptions.only2021 = faceted;
        dxfOptions.maxEdges = 100'000;  // what a 4 KB input may ask for is bounded by the reader
        const io::DxfReadResult dxf = io::readDxf(bytes, dxfOptions);
        if (dxf.drawing.has_value() == !dxf.error.empty()) std::abort();
        if (dxf.drawing) {
            const csg::Outline outline = dxf.drawing->outline();
            if (!outline.segments.empty()) checkDrawingOutline(outline);
        }
        io::SvgOptions options;
        options.faceted = faceted;
        options.center = true;
        options.maxSegments = 200000;
        const io::SvgReadResult r = io::readSvg(bytes, options);
        if (r.drawing.has_value() == !r.error.empty()) std::abort();
        if (!r.drawing) continue;
        for (const csg::Outline& outline : r.drawing->shapes) {
            if (outline.segments.empty()) std::abort();
            checkDrawingOutline(outline);
        }
    }
}

}  // namespace fuzz
