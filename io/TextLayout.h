// OpenSCAD 2021's text layout, call for call (../shared/OPENSCAD.md section 2, "text(...)"):
// fontconfig finds the font (src/FontCache.cc), HarfBuzz shapes the string and FreeType gives
// each glyph's outline (src/FreetypeRenderer.cc), and each outline point lands where
// src/DrawingCallback.cc puts it. The same Debian libraries OpenSCAD links are called the same
// way, so the glyphs, the kerning and the hinted outlines are OpenSCAD's own. Pure data out:
// turning the outlines into shapes is io/TextModule.cpp's.
//
// Units: "font units" are FreeType's 26.6 outline coordinates at a char size of 1e5/64 pt and
// 100 dpi, divided by 1e5, so that 1 em = 100/72 font units; a point v of glyph g lands at
// g.place(v, size) in the text's own coordinates (size 10: 1 em = 13.889).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "primitives/base/Math.h"

namespace io {

// text()'s parameters, with OpenSCAD's defaults. An empty string means "not given" where
// OpenSCAD defaults to the empty string: font (then "Liberation Sans:style=Regular"),
// direction and script (then detected from the text, as OpenSCAD's detect_properties does).
struct TextParams {
    std::string text;
    double size = 10.0;
    std::string font;
    std::string direction;
    std::string language = "en";
    std::string script;
    std::string halign = "left";
    std::string valign = "baseline";
    double spacing = 1.0;
};

// One piece of a glyph contour, from the previous piece's end (or the contour's start) to
// `to`, in font units: a line (degree 1), a quadratic Bezier with control point c[0]
// (degree 2) or a cubic with control points c[0], c[1] (degree 3), as FreeType's
// FT_Outline_Decompose reports them.
struct GlyphPiece {
    uint8_t degree = 1;
    csg::Vec2 c[2]{};
    csg::Vec2 to{};
};

struct GlyphContour {
    csg::Vec2 start{};
    std::vector<GlyphPiece> pieces;  // closed: the last piece ends at start
};

struct PlacedGlyph {
    std::vector<GlyphContour> contours;  // none for a space
    // OpenSCAD's set_glyph_offset: the halign/valign offset plus HarfBuzz's glyph offset.
    csg::Vec2 offset{0.0};
    // OpenSCAD's pen: the sum of the previous glyphs' advances times spacing.
    csg::Vec2 advance{0.0};

    // Where font-unit point v lands: DrawingCallback::add_vertex's size * (v + offset +
    // advance), in that order of operations, so that the doubles are OpenSCAD's.
    csg::Vec2 place(csg::Vec2 v, double size) const { return size * ((v + offset) + advance); }
};

struct TextLayout {
    // One per glyph HarfBuzz made and FreeType loaded, in HarfBuzz's order.
    std::vector<PlacedGlyph> glyphs;
    // OpenSCAD's messages where it reports and goes on (a glyph that would not load) and
    // csgray's where there is no font at all. An unknown halign or valign aligns as left or
    // baseline; OpenSCAD's message for it is the caller's to give, at the argument.
    std::vector<std::string> warnings;
    std::string fontFile;    // the file fontconfig chose; empty when none was found
    std::string fontFamily;  // FreeType's family and style names of that face
    std::string fontStyle;
};

// The scale factors of OpenSCAD 2021's FreetypeRenderer: outline coordinates are divided by
// kOutlineScale, pen advances and HarfBuzz offsets multiplied by kAdvanceUnscale =
// 1 / 1.024e5, a factor 1/1.024 off (OpenSCAD's own comment: "Not sure if overall scale factor
// of 1000/1024 is mistake, but keeping ratio for compatibility"). Debian's openscad is 2021.01,
// so csgray keeps the bug to place glyphs where users' OpenSCAD does (OPENSCAD.md section 2:
// the H -> H advance at size 10 is 9.7928, not 10.0278; OpenSCAD fixed it after 2021).
inline constexpr double kOutlineScale = 1e5;
inline constexpr double kAdvanceUnscale = 1.0 / 1.024e5;

// Lays out params.text as OpenSCAD 2021 does. Thread-safe (one lock around the font
// libraries). An empty string, or a font that cannot be found, gives no glyphs.
TextLayout layoutText(const TextParams& params);

}  // namespace io
