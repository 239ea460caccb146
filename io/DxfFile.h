// DXF drawings as OpenSCAD 2021 reads them (src/dxfdata.cc `DxfData::DxfData`,
// `fixup_path_direction`, `toPolygon2d`): the 2-D geometry of the ENTITIES section (one layer
// or all) and of the blocks it INSERTs, chained into paths and filled even-odd, and the
// DIMENSION entities that dxf_dim() measures. ../shared/OPENSCAD.md §2 states the semantics.
//
// Notation: an *edge* is what OpenSCAD calls a line: two ends snapped to OpenSCAD's 1/1024 grid
// (Grid2d::align: a point moves to its grid node, or to the existing node of a neighbouring
// cell), and, when curves are exact, possibly an arc between them. Points that snap to one node
// are one point, the very same doubles, which is what chaining compares and what the crossing
// parity of csg::Outline needs. A *path* is a chain of edges as OpenSCAD extracts them: first
// the open chains (from an end no other edge touches), then the closed ones.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/Faceting.h"
#include "primitives/Outline.h"

namespace io {

struct DxfOptions {
    std::string layer;      // the layer to read; empty: every layer
    csg::Vec2 origin{0.0};  // subtracted from the file's coordinates, then...
    double scale = 1.0;     // ... multiplied by this (OpenSCAD's order)
    // CIRCLE, ARC, ELLIPSE and (not OpenSCAD) bulges: exact arcs, or OpenSCAD's chords with
    // these settings (CIRCLE frag(r) chords, ARC ceil(frag(r) sweep / 360), ELLIPSE
    // ceil(frag(r_major) sweep / 360)).
    bool faceted = true;
    FragmentSettings fragments;
    // Read only what OpenSCAD 2021 reads: LWPOLYLINE bulges are straight (with a warning) and
    // POLYLINE, VERTEX and SEQEND are unsupported entities. Otherwise csgray reads both as the
    // file means them.
    bool only2021 = true;
    // Most edges the drawing may have; more is an error (a circle with $fn = 1e9).
    uint64_t maxEdges = 10'000'000;
};

// A DIMENSION entity, as OpenSCAD keeps it: coords[k] holds group codes 10 + k and 20 + k
// (codes 11, 12 and 16 scaled only, the others moved by the origin too, as OpenSCAD does).
struct DxfDimension {
    int type = 0;  // group 70
    csg::Vec2 coords[7]{};
    double angle = 0.0;   // group 50, degrees
    double length = 0.0;  // group 40
    std::string name;     // group 1 (the dimension's text, which dxf_dim() looks up)
};

struct DxfPath {
    std::vector<csg::Vec2> points;  // q0 .. qn, grid-snapped
    std::vector<uint32_t> edges;    // e1 .. en: edge i joins points i and i + 1 (DxfDrawing::edges)
    bool closed = false;            // found in OpenSCAD's second pass (closed chains)
};

struct DxfWarning {
    uint32_t line = 0;  // of the DXF file; 0: the whole file
    std::string message;
};

struct DxfDrawing {
    // Lines and arcs (Segment2::Kind::Line or Arc) whose start() and finish() are snapped ends.
    std::vector<csg::Segment2> edges;
    std::vector<DxfPath> paths;
    std::vector<DxfDimension> dimensions;
    // Entities read as nothing, by type, in the order first met, with their counts (OpenSCAD's
    // "Unsupported DXF Entity" warning, which the caller words).
    std::vector<std::pair<std::string, uint64_t>> unsupported;
    std::vector<DxfWarning> warnings;

    // OpenSCAD's polygon of the paths (toPolygon2d): each path's edges, an open path closed by a
    // straight line from its last point to its first, all even-odd. Edges that are arcs stay
    // arcs. Empty when the drawing has no paths.
    csg::Outline outline() const;
};

struct DxfReadResult {
    std::optional<DxfDrawing> drawing;
    std::string error;        // when drawing is empty
    bool unreadable = false;  // the file could not be opened (an I/O failure)
    uint32_t line = 0;        // where in the file the error is; 0: nowhere in particular
};

// Reads DXF text (ASCII DXF, any line ending). Malformed input (a group code that is not an
// integer, a code without a value, a number that is not a finite number where one is due, an
// entity without the coordinates it needs, a coordinate beyond +-2^40) is an error with its
// line; entities csgray does not read are counted in `unsupported`.
DxfReadResult readDxf(std::string_view text, const DxfOptions& options);
// The same on a file's bytes.
DxfReadResult readDxfFile(const std::filesystem::path& file, const DxfOptions& options);

}  // namespace io
