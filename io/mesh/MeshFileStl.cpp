// STL, binary (the default: a quarter of ASCII's size, and what slicers read fastest) or ASCII:
// one facet per triangle, its corners counter-clockwise seen from outside and its normal the
// right-hand one of the float corners written (zero for a degenerate facet, as the format
// allows). STL has no shared vertices and no colours; the part's units are written as they are.
#include <array>
#include <cstring>

#include "io/mesh/MeshFileDetail.h"
#include "primitives/base/AtomicFile.h"

namespace io::detail {
namespace {

using Corners = std::array<glm::vec3, 3>;

Corners cornersOf(const csg::TriangleMesh& mesh, const std::array<uint32_t, 3>& t) {
    return {glm::vec3(mesh.positions[t[0]]), glm::vec3(mesh.positions[t[1]]),
            glm::vec3(mesh.positions[t[2]])};
}

glm::vec3 facetNormal(const Corners& c) {
    const glm::vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    const float length = glm::length(n);
    return length > 0.0f ? n / length : glm::vec3(0.0f);
}

void putFloat(std::string& out, float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int i = 0; i < 4; ++i) out += char((u >> (8 * i)) & 0xff);  // little-endian
}

void putTextVector(std::string& out, const char* keyword, const glm::vec3& v) {
    out += keyword;
    for (int a = 0; a < 3; ++a) {
        out += ' ';
        appendNumber(out, v[a]);
    }
    out += '\n';
}

}  // namespace

std::optional<std::string> writeStl(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh, bool ascii) {
    std::string out;
    if (ascii) {
        out = "solid csgray\n";
        for (const auto& t : mesh.triangles) {
            const Corners c = cornersOf(mesh, t);
            putTextVector(out, "  facet normal", facetNormal(c));
            out += "    outer loop\n";
            for (const glm::vec3& p : c) putTextVector(out, "      vertex", p);
            out += "    endloop\n  endfacet\n";
        }
        out += "endsolid csgray\n";
    } else {
        if (mesh.triangles.size() > UINT32_MAX) return "too many triangles for binary STL";
        // The header must not begin with "solid": readers would take the file for ASCII.
        std::string header = "csgray binary STL";
        header.resize(80, ' ');
        out = header;
        out.reserve(84 + 50 * mesh.triangles.size());
        const uint32_t count = uint32_t(mesh.triangles.size());
        for (int i = 0; i < 4; ++i) out += char((count >> (8 * i)) & 0xff);
        for (const auto& t : mesh.triangles) {
            const Corners c = cornersOf(mesh, t);
            const glm::vec3 n = facetNormal(c);
            for (int a = 0; a < 3; ++a) putFloat(out, n[a]);
            for (const glm::vec3& p : c)
                for (int a = 0; a < 3; ++a) putFloat(out, p[a]);
            out += std::string(2, '\0');  // the attribute byte count, unused
        }
    }
    if (std::string error = csg::writeFileAtomically(file, out); !error.empty()) return error;
    return std::nullopt;
}

}  // namespace io::detail
