// OBJ: the mesh (checked to be a closed manifold by io::writeMesh) is written as text with
// one `v` per welded vertex (a closed mesh for printing) and one `vn` per crease-split vertex
// (csg/mesh/CreaseNormals.h), faces as `f v//vn`: OpenMesh's OBJ writer has one normal per
// vertex, so it could not shade box edges flat without cutting the mesh open along them.
#include <cstdio>
#include <string>

#include "csg/mesh/CreaseNormals.h"
#include "io/mesh/MeshFileDetail.h"
#include "primitives/base/AtomicFile.h"

namespace io::detail {

std::optional<std::string> writeObj(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh) {
    // Step 1: the text (9 significant digits: float positions read back exactly). The split
    // mesh keeps triangle order and corners, so its corner indices name the normals.
    const csg::TriangleMesh shaded = csg::splitAtCreases(mesh, csg::tol::kShadingCreaseDegrees);
    std::string text =
        "# csgray mesh export: " + std::to_string(mesh.triangles.size()) + " triangles\n";
    char line[128];
    for (const csg::Vec3& p : mesh.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", float(p.x), float(p.y), float(p.z));
        text += line;
    }
    for (const csg::Vec3& n : shaded.normals) {
        std::snprintf(line, sizeof line, "vn %.6g %.6g %.6g\n", n.x, n.y, n.z);
        text += line;
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& v = mesh.triangles[t];
        const auto& n = shaded.triangles[t];
        std::snprintf(line, sizeof line, "f %u//%u %u//%u %u//%u\n", v[0] + 1, n[0] + 1, v[1] + 1,
                      n[1] + 1, v[2] + 1, n[2] + 1);
        text += line;
    }

    // Step 2: atomically to the target.
    if (std::string error = csg::writeFileAtomically(file, text); !error.empty()) return error;
    return std::nullopt;
}

}  // namespace io::detail
