// Reading OBJ: `v` positions and `f` faces (polygons, as written), straight into a polygon soup; a
// backslash ending a line continues its statement on the next. Nothing else of the format matters
// to compare (texture coordinates, normals, groups, materials are skipped), and no half-edge
// structure is built: compare checks topology itself (csg::checkTopology), so a non-manifold face
// is kept and reported rather than dropped, and loading stays linear in the size of the file
// whatever the vertex valences.
#include <cstdint>

#include "io/mesh/MeshFileDetail.h"
#include "io/mesh/MeshTextScanner.h"

namespace io::detail {

PolygonMeshReadResult parseObj(std::string_view text) {
    PolygonMeshReadResult result;
    MeshTextScanner in(text, /*lineContinuations=*/true);
    PolygonMesh mesh;
    auto fail = [&](uint32_t line, uint32_t column, std::string message) {
        result.error = std::move(message);
        result.line = line;
        result.column = column;
        return result;
    };
    std::vector<uint32_t> corners;
    while (!in.atEnd()) {
        in.skipBlanks();
        const uint32_t line = in.line();
        const std::string_view keyword = in.word();
        if (keyword == "v") {
            double xyz[3];
            for (double& c : xyz) {
                in.skipBlanks();
                const uint32_t numberLine = in.line(), column = in.column();
                if (!in.number(c))
                    return fail(numberLine, column, "expected a finite number (v x y z)");
                if (!measurable(c)) return fail(numberLine, column, kUnmeasurableCoordinate);
            }
            mesh.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
        } else if (keyword == "f") {
            corners.clear();
            for (in.skipBlanks(); !in.atLineEnd(); in.skipBlanks()) {
                // A corner is v, v/vt, v//vn or v/vt/vn; only v matters here. Negative
                // indices count back from the last vertex read so far.
                const uint32_t indexLine = in.line(), column = in.column();
                int64_t index = 0;
                if (!in.integer(index))
                    return fail(indexLine, column, "expected a vertex index (f v1 v2 v3 ...)");
                const int64_t count = int64_t(mesh.positions.size());
                const int64_t zeroBased = index > 0 ? index - 1 : count + index;
                if (index == 0 || zeroBased < 0 || zeroBased >= count)
                    return fail(indexLine, column,
                                "vertex index " + std::to_string(index) + " names no vertex (" +
                                    std::to_string(count) + " read before this line)");
                corners.push_back(uint32_t(zeroBased));
                if (in.peek() == '/')
                    in.word();  // the texture and normal indices
                else if (!in.atSeparator())
                    return fail(in.line(), in.column(), "expected a vertex index (f v1 v2 v3 ...)");
            }
            if (corners.size() < 3) return fail(line, 1, "a face needs at least 3 vertices");
            mesh.faces.corners.insert(mesh.faces.corners.end(), corners.begin(), corners.end());
            mesh.faces.closeFace();
        }
        // Every other statement (vt, vn, g, o, s, usemtl, mtllib, l, p, comments) is skipped.
        in.skipLine();
    }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace io::detail
