#include "io/DrawingFile.h"

#include <algorithm>
#include <cmath>

#include "io/mesh/MeshFileDetail.h"
#include "primitives/base/AtomicFile.h"

namespace io {

namespace {

using csg::BoundaryPiece;
using csg::Contour2D;
using csg::Vec2;

constexpr double kTurn = 2.0 * csg::kPi;
// The most an SVG arc command turns: a half turn's two arcs through the same ends are told
// apart only by the flags, and rounding can tip them; a third of a turn leaves no doubt.
constexpr double kMaxSvgArc = kTurn / 3.0;

// A number as the shortest text that reads back as the same double (-0 as 0).
void put(std::string& out, double value) {
    detail::appendNumber(out, value + 0.0);
}

void putLine(std::string& out, const char* text) {
    out += text;
    out += '\n';
}

// SVG's y points down: a point (x, y) of the part is written (x, -y).
void putSvgPoint(std::string& out, Vec2 p) {
    put(out, p.x);
    out += ',';
    put(out, -p.y);
}

void putSvgPiece(std::string& out, const BoundaryPiece& p) {
    if (p.kind == BoundaryPiece::Kind::Line) {
        out += " L ";
        putSvgPoint(out, p.b);
        return;
    }
    // Negating y turns a counter-clockwise arc clockwise on the page: SVG's sweep flag 0.
    const char* flags = p.sweep > 0.0 ? " 0 0,0 " : " 0 0,1 ";
    const int steps = int(std::ceil(std::abs(p.sweep) / kMaxSvgArc));
    for (int k = 1; k <= steps; ++k) {
        out += " A ";
        put(out, p.radius);
        out += ',';
        put(out, p.radius);
        out += flags;
        putSvgPoint(out, k == steps ? p.b : p.at(double(k) / steps));
    }
}

void putDxfGroup(std::string& out, const char* code, double value) {
    putLine(out, code);
    put(out, value);
    out += '\n';
}

// Degrees in [0, 360), as DXF angles are read.
double dxfDegrees(double radians) {
    const double d = std::fmod(radians * (180.0 / csg::kPi), 360.0);
    return d < 0.0 ? d + 360.0 : d;
}

void putDxfPiece(std::string& out, const BoundaryPiece& p) {
    if (p.kind == BoundaryPiece::Kind::Line) {
        putLine(out, "  0\nLINE\n  8\n0");
        putDxfGroup(out, " 10", p.a.x);
        putDxfGroup(out, " 20", p.a.y);
        putDxfGroup(out, " 11", p.b.x);
        putDxfGroup(out, " 21", p.b.y);
        return;
    }
    const bool whole = p.a == p.b;
    putLine(out, whole ? "  0\nCIRCLE\n  8\n0" : "  0\nARC\n  8\n0");
    putDxfGroup(out, " 10", p.center.x);
    putDxfGroup(out, " 20", p.center.y);
    putDxfGroup(out, " 40", p.radius);
    if (whole) return;
    // An ARC turns counter-clockwise from its start angle to its end angle.
    const double from = p.sweep > 0.0 ? p.angle0 : p.angle0 + p.sweep;
    putDxfGroup(out, " 50", dxfDegrees(from));
    putDxfGroup(out, " 51", dxfDegrees(from + std::abs(p.sweep)));
}

}  // namespace

DrawingFormat drawingFormatOf(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".svg") return DrawingFormat::Svg;
    if (ext == ".dxf") return DrawingFormat::Dxf;
    return DrawingFormat::Unknown;
}

std::string svgText(const std::vector<Contour2D>& contours) {
    // OpenSCAD's page: the integer box around the shape, in millimetres, y negated.
    csg::Bounds2 box;
    for (const Contour2D& contour : contours)
        for (const BoundaryPiece& p : contour) {
            const csg::Bounds2 b = p.bounds();
            box.add(b.lo);
            box.add(b.hi);
        }
    double minX = 0.0, minY = 0.0, width = 0.0, height = 0.0;
    if (!box.empty()) {
        minX = std::floor(box.lo.x);
        minY = std::floor(-box.hi.y);
        width = std::ceil(box.hi.x) - minX;
        height = std::ceil(-box.lo.y) - minY;
    }
    std::string out;
    putLine(out, "<?xml version=\"1.0\" standalone=\"no\"?>");
    putLine(out,
            "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" "
            "\"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\">");
    out += "<svg width=\"";
    put(out, width);
    out += "mm\" height=\"";
    put(out, height);
    out += "mm\" viewBox=\"";
    for (double v : {minX, minY, width}) put(out, v), out += ' ';
    put(out, height);
    putLine(out, "\" xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\">");
    putLine(out, "<title>csgray drawing</title>");
    putLine(out, "<path d=\"");
    for (const Contour2D& contour : contours) {
        if (contour.empty()) continue;
        out += "M ";
        putSvgPoint(out, contour.front().a);
        // z draws a closing line itself.
        const bool lastIsLine = contour.back().kind == BoundaryPiece::Kind::Line;
        for (size_t k = 0; k + (lastIsLine ? 1 : 0) < contour.size(); ++k)
            putSvgPiece(out, contour[k]);
        putLine(out, " z");
    }
    putLine(out, "\" stroke=\"black\" fill=\"lightgray\" stroke-width=\"0.5\"/>");
    putLine(out, "</svg>");
    return out;
}

std::string dxfText(const std::vector<Contour2D>& contours) {
    std::string out;
    putLine(out, "  0\nSECTION\n  2\nBLOCKS\n  0\nENDSEC");
    putLine(out, "  0\nSECTION\n  2\nENTITIES");
    for (const Contour2D& contour : contours)
        for (const BoundaryPiece& p : contour) putDxfPiece(out, p);
    putLine(out, "  0\nENDSEC");
    putLine(out, "  0\nSECTION\n  2\nOBJECTS\n  0\nDICTIONARY\n  0\nENDSEC");
    putLine(out, "  0\nEOF");
    return out;
}

std::optional<std::string> writeDrawing(const std::filesystem::path& file,
                                        const std::vector<Contour2D>& contours) {
    const DrawingFormat format = drawingFormatOf(file);
    if (format == DrawingFormat::Unknown)
        return "cannot tell the drawing format of '" + file.string() + "' (use .svg or .dxf)";
    const std::string error = csg::writeFileAtomically(
        file, format == DrawingFormat::Svg ? svgText(contours) : dxfText(contours));
    if (!error.empty()) return error;
    return std::nullopt;
}

}  // namespace io
