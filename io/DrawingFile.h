// 2-D drawings written: a 2-D part's boundary (csg/derived/Boundary2D.h) as SVG or DXF, the
// two files OpenSCAD exports a 2-D part to, laid out as OpenSCAD 2021 lays them out
// (src/export_svg.cc, src/export_dxf.cc) so that what reads OpenSCAD's reads csgray's. Where
// OpenSCAD writes a polygon, csgray writes the exact curves its boundary has: circular arcs
// as SVG `A` commands and DXF ARC and CIRCLE entities, coordinates as the shortest decimals
// that read back as the very doubles (OpenSCAD prints 6 digits).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "csg/derived/Boundary2D.h"

namespace io {

enum class DrawingFormat { Unknown, Svg, Dxf };

// By extension, case-insensitively.
DrawingFormat drawingFormatOf(const std::filesystem::path& file);

// The drawing's text. SVG: one path of every contour (y negated: SVG's y points down), in
// millimetres, the viewBox the integer box around the shape, filled light grey with a black
// outline as OpenSCAD draws it. DXF: a LINE, ARC or CIRCLE entity per piece on layer 0.
std::string svgText(const std::vector<csg::Contour2D>& contours);
std::string dxfText(const std::vector<csg::Contour2D>& contours);

// Writes the contours to file in the format of its extension, atomically: on failure no file
// is left behind. Returns the error, or nothing on success.
std::optional<std::string> writeDrawing(const std::filesystem::path& file,
                                        const std::vector<csg::Contour2D>& contours);

}  // namespace io
