// OpenSCAD 2021's surface(file = "x.dat" | "x.png", center = false, invert = false,
// convexity): a heightmap read from a text grid or the luminance of a PNG, as the closed
// triangle mesh OpenSCAD builds of it (../shared/OPENSCAD.md section 8), kept as a
// primitives/Polyhedron.h mesh: the same vertices, the same four triangles per cell fanned to
// the cell's centre, vertical walls down to a flat base at min(0, lowest height - 1).
// csgray's own surface(f = "polynomial", bbox) is io/SurfaceModule.h; surfaceModule() there
// hands a call to heightmapModule() when isHeightmapCall() says it is OpenSCAD's form.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "io/Evaluator.h"
#include "primitives/Polyhedron.h"

namespace io {

// Most grid points a heightmap may have (1024 x 1024): four triangles a cell, so at most
// ~2^22 triangles, well within Polyhedron::kMaxTriangles, and a few hundred MB at most. A
// bigger .dat or PNG is an error at the call, found from its header or while reading, before
// anything that size is built.
inline constexpr uint64_t kMaxHeightmapPoints = uint64_t(1) << 20;
// Largest .dat file read, in bytes (a grid of kMaxHeightmapPoints numbers needs far less).
inline constexpr uint64_t kMaxHeightmapFileBytes = uint64_t(64) << 20;

// A heightmap as OpenSCAD 2021 holds it: row r, column c has height at(r, c), 0 where the file
// gave none (a short row); rows and columns are 1 + the largest index given.
struct Heightmap {
    int rows = 0, columns = 0;
    std::vector<double> heights;  // rows * columns, row-major
    double lowest = 0.0;          // least height actually given (0 when none)
    bool any = false;             // whether any height was given
    double at(int r, int c) const { return heights[size_t(r) * size_t(columns) + size_t(c)]; }
    // The base plane: min(0, lowest given height - 1), as OpenSCAD 2021 computes it.
    double base() const { return any ? std::min(0.0, lowest - 1.0) : 0.0; }
};

// The result of reading a .dat text: the map, or an error (too many points); `warning` is
// OpenSCAD's "Illegal value" message when reading stopped at a token that is not a number.
struct DatRead {
    Heightmap map;
    std::string error;
    std::string warning;
};

// Parses .dat text as OpenSCAD 2021's read_dat does: lines trimmed, empty lines and lines
// starting with '#' skipped, numbers separated by spaces or tabs; the first token that is not
// a finite number stops reading (with a warning, unless it is on a last line with no newline,
// where OpenSCAD is silent); what was read before it stays, its partial row included.
DatRead parseDat(std::string_view text, const std::string& fileName);

// The mesh's corners and faces for map at OpenSCAD's positions (x = column, y = row, shifted
// by -(columns - 1) / 2 and -(rows - 1) / 2 when center). Needs rows, columns >= 2.
void heightmapMesh(const Heightmap& map, bool center, std::vector<csg::Vec3>& points,
                   csg::PolygonFaces& faces);

// Whether a surface() call is OpenSCAD's heightmap form, read from its syntax alone (so that
// nothing is evaluated twice): an argument named file, center, invert or convexity, or none
// named f, bbox, solver or tolerance and no second positional argument written as a vector
// literal (csgray's bbox).
bool isHeightmapCall(const InstantiationStmt& s);

// The built-in module for that form: file (found beside the .scad file that calls it, else
// beside the main file with OpenSCAD's deprecation warning), a PNG by its signature, else .dat.
Instance heightmapModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                         const GeomState& state);

}  // namespace io
