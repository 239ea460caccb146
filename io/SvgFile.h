// SVG drawings as OpenSCAD 2021 reads them (src/import_svg.cc, src/libsvg/): the shapes of the
// document (path, rect, circle, ellipse, line, polyline, polygon; text is not drawn, nothing
// inside <defs> is), each under the transforms of its own element and of its enclosing groups,
// then mapped from user units to millimetres by the page (the last <svg> element's width,
// height, viewBox and preserveAspectRatio, at `dpi` for unitless lengths) with y flipped.
// ../shared/OPENSCAD.md §2 states the semantics; io/SvgShapes.h how an element becomes
// segments (filled, or stroked when open).
//
// The result is one even-odd outline per shape; the drawing is their union. Curves are exact
// (Beziers stay Beziers, circles, ellipses and arcs elliptic arcs, mapped by the transforms)
// unless `faceted`, when they are OpenSCAD's chords.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "primitives/Outline.h"

namespace io {

struct SvgOptions {
    double dpi = 72.0;     // for lengths without a unit (OpenSCAD's default)
    bool center = false;   // centre the drawing's bounding box on the origin
    bool faceted = false;  // OpenSCAD's chords instead of exact curves
    // Most segments the drawing may have (strokes count what Clipper makes); more is an error.
    uint64_t maxSegments = 10'000'000;
};

struct SvgWarning {
    uint32_t line = 0;  // of the SVG file; 0: the whole file
    std::string message;
};

struct SvgDrawing {
    std::vector<csg::Outline> shapes;  // millimetres, each even-odd, none empty
    std::vector<SvgWarning> warnings;
    uint64_t segments = 0;  // every segment made, strokes' included
};

struct SvgReadResult {
    std::optional<SvgDrawing> drawing;
    std::string error;        // when drawing is empty
    bool unreadable = false;  // the file could not be opened (an I/O failure)
    uint32_t line = 0;        // where in the file the error is; 0: nowhere in particular
};

// Reads SVG text. Malformed XML, path data or number lists, a number that is not finite or is
// beyond 2^40, a transform that is not finite and a drawing beyond maxSegments are errors with
// their line; what OpenSCAD reads differently from the file's plain meaning (a length with a
// unit where it takes none, a transform with the wrong number of arguments) is a warning.
SvgReadResult readSvg(std::string_view text, const SvgOptions& options);
// The same on a file's bytes.
SvgReadResult readSvgFile(const std::filesystem::path& file, const SvgOptions& options);

}  // namespace io
