// What the mesh fuzzer (fuzz_mesh.cpp) and the mesh corpus replay (fuzz_replay mesh) do with
// one input: parse it as every mesh format compare reads, check the readers' promises, and run
// compare's mesh checks on any mesh that comes out. Any crash, hang, sanitizer report or
// abort() here is a bug.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string_view>

#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/TriangleBvh.h"
#include "io/mesh/MeshFile.h"
#include "primitives/base/Tolerances.h"

namespace fuzz {

inline void readMeshInput(std::string_view bytes) {
    using io::MeshFormat;
    for (const MeshFormat format :
         {MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Glb, MeshFormat::Gltf}) {
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
}

}  // namespace fuzz
