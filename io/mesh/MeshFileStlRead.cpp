// Reading STL, binary or ASCII, straight into a polygon soup (the corners of each facet; readMesh
// and import() weld equal positions). No half-edge structure is built: OpenMesh's
// reader spent time quadratic in a vertex's valence adding faces around it (a 200,000-segment
// cone's apex), and dropped faces its structure could not hold, which compare should report.
// The facet normals are not read: the corners' order gives the orientation compare checks.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "io/mesh/MeshFileDetail.h"
#include "io/mesh/MeshTextScanner.h"

namespace io::detail {
namespace {

constexpr size_t kHeaderBytes = 80 + 4;  // a free header, then the facet count
constexpr size_t kFacetBytes = 50;       // normal, 3 corners (12 floats), 2 attribute bytes

uint32_t facetCount(std::string_view bytes) {
    uint32_t n = 0;
    for (int i = 3; i >= 0; --i) n = n << 8 | uint8_t(bytes[size_t(80 + i)]);  // little-endian
    return n;
}

float floatAt(std::string_view bytes, size_t offset) {
    uint32_t u = 0;
    for (int i = 3; i >= 0; --i) u = u << 8 | uint8_t(bytes[offset + size_t(i)]);
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Binary STL: little-endian float corners, each facet's three in order.
PolygonMeshReadResult readBinary(std::string_view bytes) {
    PolygonMeshReadResult result;
    const size_t facets = facetCount(bytes);
    PolygonMesh mesh;
    mesh.positions.reserve(3 * facets);
    mesh.faces.corners.reserve(3 * facets);
    mesh.faces.faceStart.reserve(facets + 1);
    for (size_t f = 0; f < facets; ++f) {
        const size_t corners = kHeaderBytes + f * kFacetBytes + 12;
        const uint32_t first = uint32_t(mesh.positions.size());
        for (size_t c = 0; c < 3; ++c) {
            const size_t at = corners + 12 * c;
            const csg::Vec3 p(floatAt(bytes, at), floatAt(bytes, at + 4), floatAt(bytes, at + 8));
            if (!measurable(p)) {
                result.error =
                    "binary STL: facet " + std::to_string(f + 1) + ": " + kUnmeasurableCoordinate;
                return result;
            }
            mesh.positions.push_back(p);
        }
        mesh.faces.add({first, first + 1, first + 2});
    }
    result.mesh = std::move(mesh);
    return result;
}

// ASCII STL: solid NAME, then per facet "facet normal n n n / outer loop / vertex x y z (3 or
// more: one polygon) / endloop / endfacet", then endsolid NAME; more solids may follow.
PolygonMeshReadResult readAscii(std::string_view text) {
    PolygonMeshReadResult result;
    MeshTextScanner in(text);
    PolygonMesh mesh;
    uint32_t line = 0, column = 0;
    auto fail = [&](std::string message) {
        result.error = std::move(message);
        result.line = line;
        result.column = column;
        return result;
    };
    // The next word, with its position kept for an error.
    auto next = [&]() {
        in.skipWhitespace();
        line = in.line();
        column = in.column();
        return in.word();
    };
    auto expect = [&](std::string_view keyword) { return sameWord(next(), keyword); };
    // A corner's x y z, or the error (its position kept).
    auto corner = [&](csg::Vec3& p) -> const char* {
        for (int k = 0; k < 3; ++k) {
            in.skipBlanks();
            line = in.line();
            column = in.column();
            if (!in.number(p[k])) return "expected a finite number (vertex x y z)";
            if (!measurable(p[k])) return kUnmeasurableCoordinate;
        }
        return nullptr;
    };

    size_t corners = 0;
    for (std::string_view word = next(); !word.empty(); word = next()) {
        if (!sameWord(word, "solid")) return fail("expected 'solid'");
        in.skipLine();  // the solid's name
        for (word = next(); !sameWord(word, "endsolid"); word = next()) {
            if (word.empty()) break;  // a missing endsolid is forgiven
            if (!sameWord(word, "facet")) return fail("expected 'facet' or 'endsolid'");
            if (!expect("normal")) return fail("expected 'normal'");
            // The normal is not used (compare takes the corners' order), so it is only
            // skipped: writers put "nan" there for degenerate facets.
            for (int k = 0; k < 3; ++k) {
                in.skipBlanks();
                line = in.line();
                column = in.column();
                if (in.word().empty()) return fail("expected 3 numbers (facet normal x y z)");
            }
            if (!expect("outer")) return fail("expected 'outer loop'");
            if (!expect("loop")) return fail("expected 'outer loop'");
            corners = 0;
            for (word = next(); sameWord(word, "vertex"); word = next()) {
                csg::Vec3 p;
                if (const char* error = corner(p)) return fail(error);
                mesh.faces.corners.push_back(uint32_t(mesh.positions.size()));
                mesh.positions.push_back(p);
                ++corners;
            }
            if (!sameWord(word, "endloop"))
                return fail(corners < 3 ? "expected 'vertex'" : "expected 'endloop'");
            if (corners < 3) return fail("a facet needs at least 3 vertices");
            if (!expect("endfacet")) return fail("expected 'endfacet'");
            mesh.faces.closeFace();
        }
        in.skipLine();  // endsolid's name
    }
    result.mesh = std::move(mesh);
    return result;
}

bool startsWithSolid(std::string_view bytes) {
    size_t i = 0;
    while (i < bytes.size() && std::isspace(uint8_t(bytes[i]))) ++i;
    return bytes.size() - i >= 5 && sameWord(bytes.substr(i, 5), "solid");
}

}  // namespace

PolygonMeshReadResult parseStl(std::string_view bytes) {
    PolygonMeshReadResult result;
    // A binary file's size is fixed by its facet count; its free header may start with
    // "solid" too (several exporters write that), so the size decides first.
    if (bytes.size() >= kHeaderBytes &&
        bytes.size() == kHeaderBytes + kFacetBytes * uint64_t(facetCount(bytes)))
        return readBinary(bytes);
    if (startsWithSolid(bytes)) return readAscii(bytes);
    if (bytes.size() < kHeaderBytes)
        result.error = "not an STL file: too short for a binary STL and no 'solid' to start ASCII";
    else
        result.error = "binary STL: the header says " + std::to_string(facetCount(bytes)) +
                       " facets (" +
                       std::to_string(kHeaderBytes + kFacetBytes * uint64_t(facetCount(bytes))) +
                       " bytes), the file has " + std::to_string(bytes.size()) + " bytes";
    return result;
}

}  // namespace io::detail
