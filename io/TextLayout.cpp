// OpenSCAD 2021's FontCache, FreetypeRenderer::detect_properties and FreetypeRenderer::render,
// call for call (the tag openscad-2021.01: src/FontCache.cc, src/FreetypeRenderer.cc,
// src/DrawingCallback.cc). Where this file differs in form (no Eigen, no Polygon2d, one lock),
// the values computed are the same; comments name the OpenSCAD function each step follows.
#include "io/TextLayout.h"

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include <hb-ft.h>
#include <hb.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string_view>
#include FT_FREETYPE_H
#include FT_GLYPH_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_IDS_H

namespace io {

namespace {

using csg::Vec2;

// FontCache::DEFAULT_FONT.
constexpr const char* kDefaultFont = "Liberation Sans:style=Regular";

// fontconfig's configuration with OpenSCAD's extra font folders, FreeType, and the faces
// found so far by the name they were asked for (FontCache::get_font). OpenSCAD evicts faces
// beyond a few; a face is the same face whenever it is loaded, so csgray keeps them all.
// Used only under layoutMutex(): FreeType's library and faces are not thread-safe.
class FontLibrary {
public:
    static FontLibrary& instance() {
        static FontLibrary library;
        return library;
    }
    bool ok() const { return config_ && library_; }
    struct Found {
        FT_Face face = nullptr;  // null when fontconfig finds no file
        std::string file;
    };
    // The face for a font name as text() was given it.
    const Found& face(const std::string& font) {
        auto it = faces_.find(font);
        if (it == faces_.end()) it = faces_.emplace(font, findFace(font)).first;
        return it->second;
    }

private:
    FontLibrary();
    Found findFace(const std::string& font) const;
    bool tryCharmap(FT_Face face, int platform, int encoding) const;

    FcConfig* config_ = nullptr;
    FT_Library library_ = nullptr;
    std::map<std::string, Found> faces_;
};

// FontCache::FontCache: the system configuration plus $HOME/.fonts and the folders of
// OPENSCAD_FONT_PATH (':'-separated), then the font list is built. (Debian's openscad has no
// bundled fonts folder, the first one OpenSCAD would add.)
FontLibrary::FontLibrary() {
    config_ = FcInitLoadConfig();
    if (!config_) return;
    auto addDir = [&](const std::filesystem::path& dir) {
        std::error_code ec;
        if (!std::filesystem::is_directory(dir, ec)) return;
        FcConfigAppFontAddDir(config_, reinterpret_cast<const FcChar8*>(dir.c_str()));
    };
    if (const char* home = std::getenv("HOME")) addDir(std::filesystem::path(home) / ".fonts");
    if (const char* paths = std::getenv("OPENSCAD_FONT_PATH")) {
        std::string_view rest(paths);
        while (true) {
            const size_t colon = rest.find(':');
            const std::string_view one = rest.substr(0, colon);
            if (!one.empty()) addDir(std::filesystem::absolute(std::filesystem::path(one)));
            if (colon == std::string_view::npos) break;
            rest.remove_prefix(colon + 1);
        }
    }
    FcConfigBuildFonts(config_);
    if (FT_Init_FreeType(&library_) != 0) library_ = nullptr;
}

// FontCache::try_charmap.
bool FontLibrary::tryCharmap(FT_Face face, int platform, int encoding) const {
    for (int i = 0; i < face->num_charmaps; ++i) {
        FT_CharMap charmap = face->charmaps[i];
        if (charmap->platform_id == platform &&
            (encoding < 0 || charmap->encoding_id == encoding) &&
            FT_Set_Charmap(face, charmap) == 0)
            return true;
    }
    return false;
}

// FontCache::find_face and find_face_fontconfig: the name trimmed (empty: the default font),
// parsed as a fontconfig pattern, restricted to scalable outline fonts, substituted and
// matched; a Unicode charmap if the face has one, else the first of OpenSCAD's list.
FontLibrary::Found FontLibrary::findFace(const std::string& font) const {
    const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
    auto first = std::find_if_not(font.begin(), font.end(), space);
    auto last = std::find_if_not(font.rbegin(), font.rend(), space).base();
    const std::string trimmed = first < last ? std::string(first, last) : std::string();
    const std::string lookup = trimmed.empty() ? kDefaultFont : trimmed;

    FcPattern* pattern = FcNameParse(reinterpret_cast<const FcChar8*>(lookup.c_str()));
    if (!pattern) return {};
    FcPatternAddBool(pattern, FC_OUTLINE, FcTrue);
    FcPatternAddBool(pattern, FC_SCALABLE, FcTrue);
    FcConfigSubstitute(config_, pattern, FcMatchPattern);
    FcDefaultSubstitute(pattern);
    FcResult result;
    FcPattern* match = FcFontMatch(config_, pattern, &result);
    FcPatternDestroy(pattern);
    if (!match) return {};
    FcChar8* file = nullptr;
    int index = 0;
    Found found;
    if (FcPatternGetString(match, FC_FILE, 0, &file) == FcResultMatch &&
        FcPatternGetInteger(match, FC_INDEX, 0, &index) == FcResultMatch) {
        found.file = reinterpret_cast<const char*>(file);
        if (FT_New_Face(library_, found.file.c_str(), index, &found.face) != 0) found = {};
    }
    FcPatternDestroy(match);
    FT_Face face = found.face;
    if (!face) return {};

    if (FT_Select_Charmap(face, FT_ENCODING_UNICODE) != 0) {
        const bool set = tryCharmap(face, TT_PLATFORM_MICROSOFT, TT_MS_ID_UNICODE_CS) ||
                         tryCharmap(face, TT_PLATFORM_ISO, TT_ISO_ID_10646) ||
                         tryCharmap(face, TT_PLATFORM_APPLE_UNICODE, -1) ||
                         tryCharmap(face, TT_PLATFORM_MICROSOFT, TT_MS_ID_SYMBOL_CS) ||
                         tryCharmap(face, TT_PLATFORM_MACINTOSH, TT_MAC_ID_ROMAN) ||
                         tryCharmap(face, TT_PLATFORM_ISO, TT_ISO_ID_8859_1) ||
                         tryCharmap(face, TT_PLATFORM_ISO, TT_ISO_ID_7BIT_ASCII);
        (void)set;  // OpenSCAD warns on the console only; the face is used either way
    }
    return found;
}

// FontCache::is_windows_symbol_font: a Microsoft symbol charmap whose first character lies in
// the Private Use Area page 0xf000.
bool isWindowsSymbolFont(FT_Face face) {
    if (!face->charmap || face->charmap->platform_id != TT_PLATFORM_MICROSOFT ||
        face->charmap->encoding_id != TT_MS_ID_SYMBOL_CS)
        return false;
    FT_UInt glyph = 0;
    const FT_ULong code = FT_Get_First_Char(face, &glyph);
    return glyph != 0 && code >= 0xf000;
}

std::mutex& layoutMutex() {
    static std::mutex mutex;
    return mutex;
}

// The characters of valid UTF-8 (as glib's g_utf8_validate judges it: no overlong forms, no
// surrogates, nothing past U+10FFFF), or nothing when the text is not valid.
std::optional<std::vector<uint32_t>> decodeUtf8(std::string_view s) {
    std::vector<uint32_t> out;
    for (size_t i = 0; i < s.size();) {
        const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
        const unsigned char b0 = byte(i);
        size_t length = b0 < 0x80         ? 1
                        : (b0 >> 5) == 6  ? 2
                        : (b0 >> 4) == 14 ? 3
                        : (b0 >> 3) == 30 ? 4
                                          : 0;
        if (length == 0 || i + length > s.size()) return std::nullopt;
        uint32_t c = length == 1 ? b0 : b0 & (0x7f >> length);
        for (size_t k = 1; k < length; ++k) {
            if ((byte(i + k) & 0xc0) != 0x80) return std::nullopt;
            c = (c << 6) | (byte(i + k) & 0x3f);
        }
        static constexpr uint32_t kLeast[5] = {0, 0, 0x80, 0x800, 0x10000};
        if (c < kLeast[length] || c > 0x10ffff || (c >= 0xd800 && c <= 0xdfff)) return std::nullopt;
        out.push_back(c);
        i += length;
    }
    return out;
}

std::string encodeUtf8(uint32_t c) {
    std::string s;
    if (c < 0x80) {
        s += char(c);
    } else if (c < 0x800) {
        s += char(0xc0 | (c >> 6)), s += char(0x80 | (c & 0x3f));
    } else if (c < 0x10000) {
        s += char(0xe0 | (c >> 12)), s += char(0x80 | ((c >> 6) & 0x3f));
        s += char(0x80 | (c & 0x3f));
    } else {
        s += char(0xf0 | (c >> 18)), s += char(0x80 | ((c >> 12) & 0x3f));
        s += char(0x80 | ((c >> 6) & 0x3f)), s += char(0x80 | (c & 0x3f));
    }
    return s;
}

// The text as OpenSCAD hands it to HarfBuzz: up to its first NUL (it passes c_str() and
// strlen), whole.
void addText(hb_buffer_t* buffer, const char* text) {
    const int length = int(std::strlen(text));
    hb_buffer_add_utf8(buffer, text, length, 0, length);
}

// FreetypeRenderer::is_ignored_script.
bool isIgnoredScript(hb_script_t script) {
    return script == HB_SCRIPT_COMMON || script == HB_SCRIPT_INHERITED ||
           script == HB_SCRIPT_UNKNOWN || script == HB_SCRIPT_INVALID;
}

// FreetypeRenderer::detect_properties: a script given is parsed by HarfBuzz (whatever it
// makes of it), else the one script of the text's characters (mixed scripts: unknown); a
// direction given is parsed likewise, else the script's. Both are written back as strings,
// which render() parses again.
void detectProperties(TextParams& p) {
    hb_buffer_t* buffer = hb_buffer_create();
    addText(buffer, p.text.c_str());
    unsigned count = 0;
    const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
    hb_script_t script = hb_script_from_string(p.script.c_str(), -1);
    if (script == HB_SCRIPT_INVALID) {
        for (unsigned i = 0; i < count; ++i) {
            const hb_script_t s =
                hb_unicode_script(hb_unicode_funcs_get_default(), info[i].codepoint);
            if (isIgnoredScript(s)) continue;
            if (script == HB_SCRIPT_INVALID)
                script = s;
            else if (script != s && script != HB_SCRIPT_UNKNOWN)
                script = HB_SCRIPT_UNKNOWN;
        }
    }
    hb_buffer_destroy(buffer);
    if (!isIgnoredScript(script)) {
        char tag[5] = {0, 0, 0, 0, 0};
        hb_tag_to_string(hb_script_to_iso15924_tag(script), tag);
        p.script = tag;
    }
    hb_direction_t direction = hb_direction_from_string(p.direction.c_str(), -1);
    if (direction == HB_DIRECTION_INVALID) direction = hb_script_get_horizontal_direction(script);
    p.direction = hb_direction_to_string(direction);
}

// FreetypeRenderer::calc_x_offset and calc_y_offset (their messages are the caller's).
double xOffset(const std::string& halign, double width) {
    if (halign == "right") return -width;
    if (halign == "center") return -width / 2.0;
    return 0.0;
}

double yOffset(const std::string& valign, double ascend, double descend) {
    if (valign == "top") return -ascend;
    if (valign == "center") return descend / 2.0 - ascend / 2.0;
    if (valign == "bottom") return descend;
    return 0.0;
}

// FT_Outline_Decompose's callbacks, collecting the contours in font units (OpenSCAD's
// get_scaled_vector: each coordinate divided by kOutlineScale).
Vec2 fontUnits(const FT_Vector* v) {
    return Vec2(double(v->x) / kOutlineScale, double(v->y) / kOutlineScale);
}

int moveTo(const FT_Vector* to, void* user) {
    auto& contours = *static_cast<std::vector<GlyphContour>*>(user);
    contours.push_back(GlyphContour{fontUnits(to), {}});
    return 0;
}

int lineTo(const FT_Vector* to, void* user) {
    auto& contours = *static_cast<std::vector<GlyphContour>*>(user);
    if (contours.empty()) return 0;
    contours.back().pieces.push_back(GlyphPiece{1, {}, fontUnits(to)});
    return 0;
}

int conicTo(const FT_Vector* control, const FT_Vector* to, void* user) {
    auto& contours = *static_cast<std::vector<GlyphContour>*>(user);
    if (contours.empty()) return 0;
    contours.back().pieces.push_back(GlyphPiece{2, {fontUnits(control), Vec2(0.0)}, fontUnits(to)});
    return 0;
}

int cubicTo(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
    auto& contours = *static_cast<std::vector<GlyphContour>*>(user);
    if (contours.empty()) return 0;
    contours.back().pieces.push_back(GlyphPiece{3, {fontUnits(c1), fontUnits(c2)}, fontUnits(to)});
    return 0;
}

// A glyph FreeType loaded, with HarfBuzz's position of it.
struct LoadedGlyph {
    FT_Glyph glyph = nullptr;
    hb_glyph_position_t position{};
};

}  // namespace

TextLayout layoutText(const TextParams& given) {
    TextLayout out;
    if (std::strlen(given.text.c_str()) == 0) return out;  // HarfBuzz would make no glyph
    std::lock_guard<std::mutex> lock(layoutMutex());
    TextParams params = given;
    detectProperties(params);

    // FreetypeRenderer::render.
    FontLibrary& library = FontLibrary::instance();
    if (!library.ok()) {
        out.warnings.push_back("fontconfig or FreeType could not be initialised; text() is empty");
        return out;
    }
    const FontLibrary::Found& found = library.face(params.font);
    FT_Face face = found.face;
    if (!face) {
        out.warnings.push_back("no font found for '" +
                               (params.font.empty() ? std::string(kDefaultFont) : params.font) +
                               "' (fontconfig found no scalable font); text() is empty");
        return out;
    }
    out.fontFamily = face->family_name ? face->family_name : "";
    out.fontStyle = face->style_name ? face->style_name : "";
    out.fontFile = found.file;
    if (FT_Set_Char_Size(face, 0, FT_F26Dot6(kOutlineScale), 100, 100) != 0) {
        out.warnings.push_back("Can't set font size for font " + params.font);
        return out;
    }

    hb_font_t* font = hb_ft_font_create(face, nullptr);
    hb_buffer_t* buffer = hb_buffer_create();
    hb_buffer_set_direction(buffer, hb_direction_from_string(params.direction.c_str(), -1));
    hb_buffer_set_script(buffer, hb_script_from_string(params.script.c_str(), -1));
    hb_buffer_set_language(buffer, hb_language_from_string(params.language.c_str(), -1));
    if (isWindowsSymbolFont(face)) {
        // Symbol fonts (Webdings): characters below U+0100 move to the Private Use Area page
        // 0xf000, one character at a time, as OpenSCAD adds them.
        if (const auto chars = decodeUtf8(params.text.c_str())) {
            for (uint32_t c : *chars)
                addText(buffer, encodeUtf8(c < 0x100 ? 0xf000 + c : c).c_str());
        } else {
            out.warnings.push_back("Ignoring text with invalid UTF-8 encoding: \"" + params.text +
                                   "\"");
        }
    } else {
        addText(buffer, params.text.c_str());
    }
    hb_shape(font, buffer, nullptr, 0);
    unsigned count = 0;
    const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
    const hb_glyph_position_t* position = hb_buffer_get_glyph_positions(buffer, &count);

    std::vector<LoadedGlyph> loaded;
    for (unsigned i = 0; i < count; ++i) {
        const FT_UInt index = info[i].codepoint;  // a glyph index after shaping
        FT_Glyph glyph = nullptr;
        if (FT_Load_Glyph(face, index, FT_LOAD_DEFAULT) != 0) {
            out.warnings.push_back("Could not load glyph " + std::to_string(index) +
                                   " for char at index " + std::to_string(i) + " in text '" +
                                   params.text + "'");
            continue;
        }
        if (FT_Get_Glyph(face->glyph, &glyph) != 0) {
            out.warnings.push_back("Could not get glyph " + std::to_string(index) +
                                   " for char at index " + std::to_string(i) + " in text '" +
                                   params.text + "'");
            continue;
        }
        loaded.push_back({glyph, position[i]});
    }

    // The text's extent: horizontally the sum of the advances and the largest ascent and
    // descent of the grid-fitted control boxes; vertically the widest box and the sum of the
    // vertical advances.
    const bool horizontal = HB_DIRECTION_IS_HORIZONTAL(hb_buffer_get_direction(buffer));
    double width = 0.0, ascend = 0.0, descend = 0.0;
    for (const LoadedGlyph& g : loaded) {
        FT_BBox box;
        FT_Glyph_Get_CBox(g.glyph, FT_GLYPH_BBOX_GRIDFIT, &box);
        if (horizontal) {
            width += g.position.x_advance * kAdvanceUnscale * params.spacing;
            ascend = std::max(ascend, std::max(0.0, box.yMax * kAdvanceUnscale));
            descend = std::max(descend, std::max(0.0, -box.yMin * kAdvanceUnscale));
        } else {
            width = std::max(width, (box.xMax - box.xMin) * kAdvanceUnscale);
            ascend += g.position.y_advance * kAdvanceUnscale * params.spacing;
        }
    }
    const double x0 = xOffset(params.halign, width);
    const double y0 = yOffset(params.valign, ascend, descend);

    FT_Outline_Funcs funcs{};
    funcs.move_to = moveTo;
    funcs.line_to = lineTo;
    funcs.conic_to = conicTo;
    funcs.cubic_to = cubicTo;
    funcs.shift = 0;
    funcs.delta = 0;
    Vec2 pen(0.0);
    out.glyphs.reserve(loaded.size());
    for (const LoadedGlyph& g : loaded) {
        PlacedGlyph placed;
        placed.offset = Vec2(x0 + g.position.x_offset * kAdvanceUnscale,
                             y0 + g.position.y_offset * kAdvanceUnscale);
        placed.advance = pen;
        if (g.glyph->format == FT_GLYPH_FORMAT_OUTLINE) {
            FT_Outline outline = reinterpret_cast<FT_OutlineGlyph>(g.glyph)->outline;
            FT_Outline_Decompose(&outline, &funcs, &placed.contours);
        }
        pen += Vec2(g.position.x_advance * kAdvanceUnscale * params.spacing,
                    g.position.y_advance * kAdvanceUnscale * params.spacing);
        out.glyphs.push_back(std::move(placed));
        FT_Done_Glyph(g.glyph);
    }
    hb_buffer_destroy(buffer);
    hb_font_destroy(font);
    return out;
}

}  // namespace io
