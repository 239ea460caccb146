// Mesh files: OBJ (normals split at creases), STL (binary or ASCII), 3MF, GLB and glTF (tinygltf)
// written atomically, and OBJ, STL, OFF, 3MF (our own readers: a polygon soup, no half-edge
// structure, so non-manifold input is kept for compare to report and import() to warn about),
// GLB and glTF (tinygltf) read back for comparison. Lengths are written as they are in the part
// (OpenSCAD's unit, usually mm); nothing is rescaled.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "csg/mesh/TriangleMesh.h"
#include "io/Model.h"
#include "primitives/Polyhedron.h"

namespace io {

enum class MeshFormat { Unknown, Obj, Stl, Off, ThreeMf, Glb, Gltf };

// By extension, case-insensitively.
MeshFormat meshFormatOf(const std::filesystem::path& file);

struct MeshWriteOptions {
    bool asciiStl = false;  // STL as text instead of binary
};

// Writes mesh to file in the format of its extension (OBJ, STL, 3MF, GLB or glTF; not OFF),
// atomically: on failure no file is left behind. materials is Model::materials, indexed by the
// mesh's triangleMaterial. glTF gets one primitive per material, with pbrMetallicRoughness
// from the material, and the part's Z-up frame rotated to glTF's Y-up at the root node; 3MF
// gets the materials' colours as base materials. An empty mesh writes a valid empty file. A
// mesh that is not a closed, consistently oriented 2-manifold (csg::checkTopology) is refused
// for every format. Returns the error, or nothing on success.
std::optional<std::string> writeMesh(const std::filesystem::path& file,
                                     const csg::TriangleMesh& mesh,
                                     const std::vector<Material>& materials,
                                     const MeshWriteOptions& options = {});

struct MeshReadResult {
    std::optional<csg::TriangleMesh> mesh;  // positions and triangles in the part's frame
    std::string error;                      // when mesh is empty
    bool unreadable = false;                // the file could not be opened (an I/O failure)
    uint32_t line = 0, column = 0;          // where in a text file the error is; 0: nowhere
};

// Reads an OBJ, STL, OFF, 3MF, GLB or glTF file, in time linear in its size whatever the vertex
// valences (the weld is a hash table, primitives/base/PointWelder.h). glTF node transforms are
// applied, so a csgray GLB comes back in its Z-up part frame (the root rotation undone). Vertices
// with equal positions (-0 and +0 alike) are merged (STL soups, per-material primitives), so
// topology can be checked, and where that joined sheets of solids that only touch (an edge of four
// triangles, a vertex at two cones' apex) they are told apart again (csg/mesh/TouchingSheets.h). An
// error in an OBJ or ASCII STL file (or a 3MF's model part) comes with its line and column. A
// coordinate beyond ±csg::tol::kMeshCoordinateMax (or not finite) is an error: it cannot be
// measured.
MeshReadResult readMesh(const std::filesystem::path& file);

// readMesh on bytes already read: baseDir is where a glTF's external buffers are looked up.
MeshReadResult parseMesh(std::string_view bytes, MeshFormat format,
                         const std::filesystem::path& baseDir);

// A mesh file's faces as written: positions (not welded; STL repeats each corner) and polygons
// (OBJ and OFF faces and ASCII STL facets of any corner count, 3MF triangles of every build
// item placed, each corner an index into positions). What import() builds its solid from.
struct PolygonMesh {
    std::vector<csg::Vec3> positions;
    csg::PolygonFaces faces;
};
struct PolygonMeshReadResult {
    std::optional<PolygonMesh> mesh;
    std::string error;              // when mesh is empty
    bool unreadable = false;        // the file could not be opened (an I/O failure)
    uint32_t line = 0, column = 0;  // where in a text file the error is; 0: nowhere
};

// Reads an STL (binary when its size is 84 + 50 n for the n at byte 80, as OpenSCAD decides;
// else ASCII), OBJ, OFF or 3MF file as polygons, with readMesh's limits and error positions.
PolygonMeshReadResult readPolygonMesh(const std::filesystem::path& file);
PolygonMeshReadResult parsePolygonMesh(std::string_view bytes, MeshFormat format);

}  // namespace io
