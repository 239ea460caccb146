#include "io/mesh/MeshFile.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "csg/mesh/MeshCheck.h"
#include "io/mesh/MeshFileDetail.h"
#include "primitives/base/ReadFile.h"

namespace io {

MeshFormat meshFormatOf(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".stl") return MeshFormat::Stl;
    if (ext == ".glb") return MeshFormat::Glb;
    if (ext == ".gltf") return MeshFormat::Gltf;
    return MeshFormat::Unknown;
}

std::optional<std::string> writeMesh(const std::filesystem::path& file,
                                     const csg::TriangleMesh& mesh,
                                     const std::vector<Material>& materials) {
    // Every format gets the same promise: nothing but a closed, consistently oriented
    // 2-manifold is written (a second check of dual contouring and simplification).
    const MeshFormat format = meshFormatOf(file);
    if (format != MeshFormat::Unknown && format != MeshFormat::Stl) {
        const csg::MeshTopology topo = csg::checkTopology(mesh);
        if (!topo.closedManifold())
            return "the mesh is not a closed oriented manifold (" +
                   std::to_string(topo.boundaryEdges) + " boundary, " +
                   std::to_string(topo.nonManifoldEdges) + " non-manifold, " +
                   std::to_string(topo.misorientedEdges) + " misoriented edges, " +
                   std::to_string(topo.nonManifoldVertices) + " non-manifold vertices, " +
                   std::to_string(topo.degenerateTriangles) + " degenerate triangles)";
    }
    switch (format) {
        case MeshFormat::Obj:
            return detail::writeObj(file, mesh);
        case MeshFormat::Glb:
            return detail::writeGltf(file, mesh, materials, true);
        case MeshFormat::Gltf:
            return detail::writeGltf(file, mesh, materials, false);
        case MeshFormat::Stl:
        case MeshFormat::Unknown:
            break;
    }
    return "cannot write this format (use .glb, .gltf or .obj)";
}

namespace {

const char* const kUnknownMeshFormat = "unknown mesh format (expected .obj, .stl, .glb or .gltf)";

}  // namespace

MeshReadResult readMesh(const std::filesystem::path& file) {
    const MeshFormat format = meshFormatOf(file);
    if (format == MeshFormat::Unknown) {
        MeshReadResult result;
        result.error = kUnknownMeshFormat;
        return result;
    }
    std::string bytes;
    if (const csg::ReadFailure failure = csg::readWholeFile(file, bytes);
        failure != csg::ReadFailure::None) {
        MeshReadResult result;
        result.error = failure == csg::ReadFailure::CannotRead ? "cannot read the mesh"
                                                               : "cannot open the mesh";
        result.unreadable = true;
        return result;
    }
    return parseMesh(bytes, format, file.parent_path());
}

MeshReadResult parseMesh(std::string_view bytes, MeshFormat format,
                         const std::filesystem::path& baseDir) {
    MeshReadResult result;
    switch (format) {
        case MeshFormat::Obj:
            result = detail::parseObj(bytes);
            break;
        case MeshFormat::Stl:
            result = detail::parseStl(bytes);
            break;
        case MeshFormat::Glb:
            result = detail::parseGltf(bytes, true, baseDir);
            break;
        case MeshFormat::Gltf:
            result = detail::parseGltf(bytes, false, baseDir);
            break;
        case MeshFormat::Unknown:
            result.error = kUnknownMeshFormat;
            return result;
    }
    if (result.mesh) result.mesh = csg::weldExactDuplicates(*result.mesh);
    return result;
}

}  // namespace io
