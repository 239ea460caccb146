// OBJ through OpenMesh IO: the mesh is built as an OpenMesh TriMesh (which itself refuses a
// face that would make an edge or vertex non-manifold, a second check of dual contouring)
// and written to memory, then to the target atomically.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <sstream>

#include "io/AtomicFile.h"
#include "io/MeshFileDetail.h"

namespace io::detail {

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

std::optional<std::string> writeObj(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh) {
    // Step 1: the OpenMesh mesh, with the exact vertex normals.
    OmMesh om;
    om.request_vertex_normals();
    std::vector<OmMesh::VertexHandle> handles;
    handles.reserve(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const csg::Vec3& p = mesh.positions[i];
        handles.push_back(om.add_vertex(OmMesh::Point(float(p.x), float(p.y), float(p.z))));
        if (!mesh.normals.empty()) {
            const csg::Vec3& n = mesh.normals[i];
            om.set_normal(handles.back(), OmMesh::Normal(float(n.x), float(n.y), float(n.z)));
        }
    }
    for (const auto& tri : mesh.triangles) {
        const auto face = om.add_face(handles[tri[0]], handles[tri[1]], handles[tri[2]]);
        if (!face.is_valid()) return "the mesh is not manifold: OpenMesh rejected a face";
    }

    // Step 2: OBJ text in memory (OpenMesh's progress log would clutter stderr) (9 significant
    // digits: float positions read back exactly).
    std::ostringstream text;
    text << "# csgray mesh export: " << mesh.triangles.size() << " triangles\n";
    OpenMesh::IO::Options options = OpenMesh::IO::Options::Default;
    if (!mesh.normals.empty()) options += OpenMesh::IO::Options::VertexNormal;
    omlog().disable();
    if (!mesh.empty() && !OpenMesh::IO::write_mesh(om, text, ".obj", options, 9))
        return "OpenMesh could not write the OBJ";

    // Step 3: atomically to the target.
    AtomicFile out(file);
    if (!out.ok()) return out.error();
    const std::string bytes = text.str();
    if (std::fwrite(bytes.data(), 1, bytes.size(), out.stream()) != bytes.size()) {
        out.fail("cannot write");
        return out.error();
    }
    if (!out.commit()) return out.error();
    return std::nullopt;
}

}  // namespace io::detail
