// text(): arguments bound as OpenSCAD 2021's TextModule::instantiate binds them (src/text.cc),
// the layout of io/TextLayout.h, and the glyph outlines as leaves. Notation: a "piece" is one
// line or Bezier of FreeType's decomposition, in font units (TextLayout.h); a "segment" is an
// Outline's, in the text's coordinates.
#include "io/TextModule.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "io/BoundArgs.h"
#include "io/FacetedPrimitives.h"

namespace io {

namespace {

using csg::Outline;
using csg::Segment2;
using csg::Vec2;

// DrawingCallback::curve_to, the quadratic and the cubic: the Bernstein form at parameter a,
// written as OpenSCAD writes it (the same products and sums in the same order, std::pow
// included), so that a chord's end is OpenSCAD's point to the last bit.
Vec2 quadraticAt(Vec2 pen, Vec2 c1, Vec2 to, double a) {
    return pen * std::pow(1 - a, 2) + c1 * 2.0 * std::pow(1 - a, 1) * a + to * std::pow(a, 2);
}

Vec2 cubicAt(Vec2 pen, Vec2 c1, Vec2 c2, Vec2 to, double a) {
    return pen * std::pow(1 - a, 3) + c1 * 3.0 * std::pow(1 - a, 2) * a +
           c2 * 3.0 * std::pow(1 - a, 1) * std::pow(a, 2) + to * std::pow(a, 3);
}

// One glyph's outline (see glyphOutlines).
Outline glyphOutline(const PlacedGlyph& glyph, double size, int64_t chords) {
    Outline outline;
    outline.rule = csg::FillRule::NonZero;
    const auto place = [&](Vec2 v) { return glyph.place(v, size); };
    for (const GlyphContour& contour : glyph.contours) {
        Vec2 pen = contour.start;  // font units: where the next piece starts
        Vec2 at = place(pen);      // the same point placed: the last segment's end
        // A line from `at` to q, unless it has no length; q becomes the next start.
        const auto lineTo = [&](Vec2 q) {
            if (q != at) outline.segments.push_back(Segment2::line(at, q));
            at = q;
        };
        for (const GlyphPiece& piece : contour.pieces) {
            const Vec2 end = place(piece.to);
            if (piece.degree == 1 || (chords == 0 && at == end && place(piece.c[0]) == at &&
                                      (piece.degree == 2 || place(piece.c[1]) == at))) {
                lineTo(end);
            } else if (chords == 0) {
                outline.segments.push_back(
                    piece.degree == 2
                        ? Segment2::quadratic(at, place(piece.c[0]), end)
                        : Segment2::cubic(at, place(piece.c[0]), place(piece.c[1]), end));
                at = end;
            } else {
                // OpenSCAD's a = idx * (1.0 / fn); the last chord ends at the placed end
                // itself (the formula gives it too, up to the sign of a zero).
                const double step = 1.0 / double(chords);
                for (int64_t i = 1; i <= chords; ++i) {
                    const double a = double(i) * step;
                    lineTo(i == chords ? end
                           : piece.degree == 2
                               ? place(quadraticAt(pen, piece.c[0], piece.to, a))
                               : place(cubicAt(pen, piece.c[0], piece.c[1], piece.to, a)));
                }
            }
            pen = piece.to;
        }
    }
    return outline;
}

// A string argument (dflt when not given).
std::string stringArg(Evaluator& e, const BoundArgs& b, size_t i, const char* dflt) {
    if (!b.given(i)) return dflt;
    if (!b[i].isString()) b.bad(e, i, "a string");
    return b[i].string();
}

// Evaluation steps charged per outline segment (EvaluateOptions::maxSteps, ~5 bytes a step: a
// Segment2 is about 100 bytes), so that a huge $fn runs out of budget, not out of memory.
constexpr uint64_t kSegmentSteps = 20;

// The error for a faceting finer than the evaluation budget allows.
std::string tooManySegments(const FragmentSettings& settings, int64_t n, int64_t chords,
                            uint64_t segments) {
    const bool fn = fnDecidesCount(settings);
    const std::string why = fn ? "$fn = " + formatNumber(settings.fn) + " gives "
                               : "$fa = " + formatNumber(settings.fa) +
                                     " and $fs = " + formatNumber(settings.fs) + " give ";
    return "text(): " + why + std::to_string(n) + " fragments, so " + std::to_string(chords) +
           " chords per curve (OpenSCAD's fragments / 8 + 1) and " + std::to_string(segments) +
           " outline segments, more than the evaluation budget allows; expected " +
           (fn ? "a smaller $fn" : "a larger $fa or $fs") + ", or --curves exact for exact curves";
}

// OpenSCAD's messages (FreetypeRenderer::calc_x_offset, calc_y_offset), the value appended.
const std::string kUnknownHalign =
    R"(Unknown value for the halign parameter (use "left", "right" or "center"): ')";
const std::string kUnknownValign =
    R"(Unknown value for the valign parameter (use "baseline", "bottom", "top" or "center"): ')";

constexpr const char* kForm =
    "text(text, size = 10, font, halign = \"left\", valign = \"baseline\", spacing = 1, "
    "direction = \"ltr\", language = \"en\", script = \"latin\")";

}  // namespace

int64_t textChordCount(int64_t fragments) {
    return std::max<int64_t>(fragments / 8 + 1, 2);
}

uint64_t glyphSegmentCount(const TextLayout& layout, int64_t chords) {
    uint64_t count = 0;
    for (const PlacedGlyph& glyph : layout.glyphs)
        for (const GlyphContour& contour : glyph.contours)
            for (const GlyphPiece& piece : contour.pieces)
                count += piece.degree == 1 || chords == 0 ? 1 : uint64_t(chords);
    return count;
}

std::vector<Outline> glyphOutlines(const TextLayout& layout, double size, int64_t chords) {
    std::vector<Outline> outlines;
    for (const PlacedGlyph& glyph : layout.glyphs) {
        Outline outline = glyphOutline(glyph, size, chords);
        if (!outline.segments.empty()) outlines.push_back(std::move(outline));
    }
    return outlines;
}

Instance textModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state) {
    // OpenSCAD's parameters: text, size and font by position or name, the others by name
    // only (a fourth positional argument is OpenSCAD's "Too many unnamed arguments", here an
    // error like every other module's).
    BoundArgs b = bindArgs(
        e, s, ctx,
        {"text", "size", "font", "direction", "language", "script", "halign", "valign", "spacing"},
        kForm);
    size_t positional = 0;
    for (const ArgValue& a : b.all) {
        if (!a.name.empty() || ++positional <= 3) continue;
        e.fail(a.loc, std::string("too many unnamed arguments to text(): only text, size and font "
                                  "may be given by position; expected ") +
                          kForm);
    }
    TextParams params;
    params.text = stringArg(e, b, 0, "");
    params.size = numberArg(e, b, 1, 10.0);
    params.font = stringArg(e, b, 2, "");
    params.direction = stringArg(e, b, 3, "");
    params.language = stringArg(e, b, 4, "en");
    params.script = stringArg(e, b, 5, "");
    params.halign = stringArg(e, b, 6, "left");
    params.valign = stringArg(e, b, 7, "baseline");
    params.spacing = numberArg(e, b, 8, 1.0);
    // OpenSCAD's messages for an alignment it does not know; it then aligns as left/baseline.
    const std::string& h = params.halign;
    const std::string& v = params.valign;
    if (h != "left" && h != "center" && h != "right") e.warn(b.loc(6), kUnknownHalign + h + "'");
    if (v != "baseline" && v != "bottom" && v != "top" && v != "center")
        e.warn(b.loc(7), kUnknownValign + v + "'");

    // OpenSCAD reads $fn, $fa and $fs unclamped for text, with size as the radius.
    const FragmentSettings settings = unclampedFragmentSettings(e, b, ctx);
    const int64_t chords =
        isFaceted(e.curveMode(), settings) ? textChordCount(fragments(params.size, settings)) : 0;

    // An empty text (up to its first NUL, as OpenSCAD passes it on) has no glyphs.
    if (std::strlen(params.text.c_str()) == 0) return csg::NodePtr();
    const TextLayout layout = layoutText(params);
    for (const std::string& warning : layout.warnings) e.warn(s.loc, "text(): " + warning);
    if (params.size == 0.0) return csg::NodePtr();  // every point at the origin
    // Refused before any segment is made, with the reason rather than the budget's message.
    const uint64_t segments = glyphSegmentCount(layout, chords);
    if (segments > e.budget().left / kSegmentSteps)
        e.fail(s.loc,
               tooManySegments(settings, fragments(params.size, settings), chords, segments));
    e.spend(s.loc, segments * kSegmentSteps);

    const uint32_t tag = e.sourceTag(s.loc, e.childPath(state, s.name));
    std::vector<csg::NodePtr> leaves;
    for (Outline& outline : glyphOutlines(layout, params.size, chords))
        leaves.push_back(csg::leaf(
            csg::Extrusion::plane(std::make_shared<const Outline>(std::move(outline)), "text"),
            {tag, state.material}));
    return csg::uniteAll(leaves, {tag, 0});
}

}  // namespace io
