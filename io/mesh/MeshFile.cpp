#include "io/mesh/MeshFile.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/TouchingSheets.h"
#include "io/mesh/MeshFileDetail.h"
#include "primitives/base/ReadFile.h"

namespace io {

MeshFormat meshFormatOf(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".stl") return MeshFormat::Stl;
    if (ext == ".off") return MeshFormat::Off;
    if (ext == ".3mf") return MeshFormat::ThreeMf;
    if (ext == ".glb") return MeshFormat::Glb;
    if (ext == ".gltf") return MeshFormat::Gltf;
    return MeshFormat::Unknown;
}

std::optional<std::string> writeMesh(const std::filesystem::path& file,
                                     const csg::TriangleMesh& mesh,
                                     const std::vector<Material>& materials,
                                     const MeshWriteOptions& options) {
    // Every format gets the same promise: nothing but a closed, consistently oriented
    // 2-manifold is written (a second check of dual contouring and simplification).
    const MeshFormat format = meshFormatOf(file);
    if (format != MeshFormat::Unknown && format != MeshFormat::Off) {
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
            return detail::writeStl(file, mesh, options.asciiStl);
        case MeshFormat::ThreeMf:
            return detail::write3mf(file, mesh, materials);
        case MeshFormat::Off:
        case MeshFormat::Unknown:
            break;
    }
    return "cannot write this format (use .glb, .gltf, .obj, .stl or .3mf)";
}

namespace {

const char* const kUnknownMeshFormat =
    "unknown mesh format (expected .obj, .stl, .off, .3mf, .glb or .gltf)";
const char* const kNotPolygonFormat = "unknown mesh format (expected .stl, .off, .obj or .3mf)";

// The file's bytes, or the failure as a result of type R.
template <class R>
std::optional<R> readBytes(const std::filesystem::path& file, std::string& bytes) {
    if (const csg::ReadFailure failure = csg::readWholeFile(file, bytes);
        failure != csg::ReadFailure::None) {
        R result;
        result.error = failure == csg::ReadFailure::CannotRead ? "cannot read the mesh"
                                                               : "cannot open the mesh";
        result.unreadable = true;
        return result;
    }
    return std::nullopt;
}

// Polygons cut into a fan from their first corner (compare's triangles).
MeshReadResult fanned(PolygonMeshReadResult polygons) {
    MeshReadResult result;
    result.error = std::move(polygons.error);
    result.unreadable = polygons.unreadable;
    result.line = polygons.line;
    result.column = polygons.column;
    if (!polygons.mesh) return result;
    csg::TriangleMesh mesh;
    mesh.positions = std::move(polygons.mesh->positions);
    const csg::PolygonFaces& faces = polygons.mesh->faces;
    for (size_t f = 0; f < faces.size(); ++f) {
        const uint32_t* c = faces.corners.data() + faces.faceStart[f];
        const uint32_t k = faces.faceStart[f + 1] - faces.faceStart[f];
        for (uint32_t i = 1; i + 1 < k; ++i) mesh.triangles.push_back({c[0], c[i], c[i + 1]});
    }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace

MeshReadResult readMesh(const std::filesystem::path& file) {
    const MeshFormat format = meshFormatOf(file);
    if (format == MeshFormat::Unknown) {
        MeshReadResult result;
        result.error = kUnknownMeshFormat;
        return result;
    }
    std::string bytes;
    if (auto failed = readBytes<MeshReadResult>(file, bytes)) return std::move(*failed);
    return parseMesh(bytes, format, file.parent_path());
}

MeshReadResult parseMesh(std::string_view bytes, MeshFormat format,
                         const std::filesystem::path& baseDir) {
    MeshReadResult result;
    switch (format) {
        case MeshFormat::Obj:
        case MeshFormat::Stl:
        case MeshFormat::Off:
        case MeshFormat::ThreeMf:
            result = fanned(parsePolygonMesh(bytes, format));
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
    if (result.mesh) {
        result.mesh = csg::weldExactDuplicates(*result.mesh);
        // Solids that touch along an edge or at a point (an exact boundary's contacts) are
        // written as sheets that repeat positions there (STL cannot tell them apart at all), so
        // welding joined them: separate them again (csg/mesh/TouchingSheets.h).
        csg::closedOnceSheetsSeparated(*result.mesh);
    }
    return result;
}

PolygonMeshReadResult readPolygonMesh(const std::filesystem::path& file) {
    const MeshFormat format = meshFormatOf(file);
    if (format != MeshFormat::Obj && format != MeshFormat::Stl && format != MeshFormat::Off &&
        format != MeshFormat::ThreeMf) {
        PolygonMeshReadResult result;
        result.error = kNotPolygonFormat;
        return result;
    }
    std::string bytes;
    if (auto failed = readBytes<PolygonMeshReadResult>(file, bytes)) return std::move(*failed);
    return parsePolygonMesh(bytes, format);
}

PolygonMeshReadResult parsePolygonMesh(std::string_view bytes, MeshFormat format) {
    switch (format) {
        case MeshFormat::Obj:
            return detail::parseObj(bytes);
        case MeshFormat::Stl:
            return detail::parseStl(bytes);
        case MeshFormat::Off:
            return detail::parseOff(bytes);
        case MeshFormat::ThreeMf:
            return detail::parse3mf(bytes);
        default:
            break;
    }
    PolygonMeshReadResult result;
    result.error = kNotPolygonFormat;
    return result;
}

}  // namespace io
