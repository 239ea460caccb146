// Reading OFF (Geomview's Object File Format, what OpenSCAD exports and imports): a header
// keyword ending in "OFF" (OFF, COFF, NOFF, CNOFF, STOFF: the letters announce per-vertex extras,
// which are skipped), the counts "vertices faces edges", then one vertex per line (x y z and any
// extras) and one face per line (k, then k indices from 0, then an optional colour). '#' starts
// a comment; blank lines are skipped. The binary variant ("OFF BINARY") and 4-D ones are
// refused by name.
#include <cstdint>

#include "io/mesh/MeshFileDetail.h"
#include "io/mesh/MeshTextScanner.h"

namespace io::detail {

namespace {

// Skips blanks, newlines and '#' comments, so the next token is a value.
void skipToToken(MeshTextScanner& in) {
    for (;;) {
        in.skipWhitespace();
        if (in.peek() != '#') return;
        in.skipLine();
    }
}

bool endsWithOff(std::string_view word) {
    return word.size() >= 3 && sameWord(word.substr(word.size() - 3), "off");
}

}  // namespace

PolygonMeshReadResult parseOff(std::string_view text) {
    PolygonMeshReadResult result;
    MeshTextScanner in(text);
    auto fail = [&](uint32_t line, uint32_t column, std::string message) {
        result.error = std::move(message);
        result.line = line;
        result.column = column;
        return result;
    };
    // Step 1: the header keyword and the counts (on its line or the next).
    skipToToken(in);
    uint32_t line = in.line(), column = in.column();
    const std::string_view keyword = in.word();
    if (!endsWithOff(keyword)) return fail(line, column, "expected 'OFF' to start an OFF file");
    if (keyword.find('4') != std::string_view::npos || keyword.find('n') != std::string_view::npos)
        return fail(line, column, "4-D and n-D OFF files are not supported");
    MeshTextScanner ahead = in;
    ahead.skipBlanks();
    if (sameWord(ahead.word(), "binary")) return fail(line, column, "binary OFF is not supported");
    int64_t counts[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        skipToToken(in);
        line = in.line(), column = in.column();
        if (!in.integer(counts[k]) || counts[k] < 0)
            return fail(line, column, "expected the counts 'vertices faces edges'");
    }
    // Counts beyond what the file's bytes can hold are a malformed file, not an allocation.
    if (uint64_t(counts[0]) > text.size() || uint64_t(counts[1]) > text.size())
        return fail(line, column, "the counts exceed what the file holds");
    in.skipLine();
    PolygonMesh mesh;
    mesh.positions.reserve(size_t(counts[0]));
    // Step 2: the vertices, x y z and any extras to the line's end.
    for (int64_t v = 0; v < counts[0]; ++v) {
        csg::Vec3 p;
        skipToToken(in);
        for (int k = 0; k < 3; ++k) {
            in.skipBlanks();
            line = in.line(), column = in.column();
            if (!in.number(p[k]))
                return fail(line, column,
                            "expected a finite number (vertex " + std::to_string(v) + ": x y z)");
            if (!measurable(p[k])) return fail(line, column, kUnmeasurableCoordinate);
        }
        mesh.positions.push_back(p);
        in.skipLine();
    }
    // Step 3: the faces, k i1 .. ik and an optional colour to the line's end.
    mesh.faces.faceStart.reserve(size_t(counts[1]) + 1);
    for (int64_t f = 0; f < counts[1]; ++f) {
        skipToToken(in);
        line = in.line(), column = in.column();
        int64_t k = 0;
        if (!in.integer(k) || k < 3)
            return fail(line, column,
                        "expected a corner count of at least 3 (face " + std::to_string(f) + ")");
        for (int64_t c = 0; c < k; ++c) {
            in.skipBlanks();
            line = in.line(), column = in.column();
            int64_t index = -1;
            if (!in.integer(index))
                return fail(line, column,
                            "expected a vertex index (face " + std::to_string(f) + ": k i1 .. ik)");
            if (index < 0 || index >= counts[0])
                return fail(line, column,
                            "vertex index " + std::to_string(index) + " names no vertex (" +
                                std::to_string(counts[0]) + " vertices)");
            mesh.faces.corners.push_back(uint32_t(index));
        }
        mesh.faces.closeFace();
        in.skipLine();
    }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace io::detail
