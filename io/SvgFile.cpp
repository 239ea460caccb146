// SVG documents: see io/SvgFile.h, and ../shared/OPENSCAD.md §2 for the OpenSCAD 2021
// behaviour followed (src/import_svg.cc, src/libsvg/libsvg.cc, shape.cc, svgpage.cc, util.cc,
// transformation.cc).
//
// Notation: *user units* are the coordinates of the file; an element's *transform* maps its
// user units to its parent's, the *page map* the document's user units to millimetres.
#include "io/SvgFile.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "io/Degrees.h"
#include "io/SvgShapes.h"

namespace io {

namespace {

using csg::Bounds2;
using csg::Segment2;
using csg::Vec2;
namespace xml = tinyxml2;

// x -> m x + t.
struct Affine {
    glm::dmat2 m{1.0};
    Vec2 t{0.0};
    Affine then(const Affine& inner) const { return {m * inner.m, m * inner.t + t}; }
    bool finite() const {
        for (int c = 0; c < 2; ++c)
            for (int r = 0; r < 2; ++r)
                if (!std::isfinite(m[c][r])) return false;
        return std::isfinite(t.x) && std::isfinite(t.y);
    }
};

// A 2x3 matrix [a c e; b d f] (SVG's order).
Affine matrixOf(double a, double b, double c, double d, double e, double f) {
    Affine x;
    x.m = glm::dmat2(a, b, c, d);  // columns
    x.t = Vec2(e, f);
    return x;
}

// libsvg's units (util.h unit_t); Undefined: no length could be read.
enum class Unit { Undefined, None, Percent, Em, Ex, Px, In, Cm, Mm, Pt, Pc };
struct Length {
    double number = 0.0;
    Unit unit = Unit::Undefined;
};
enum class Align { None, Min, Mid, Max };

struct Page {
    Length width, height;
    bool viewBoxValid = false;
    double viewBox[4] = {0, 0, 0, 0};  // x, y, width, height
    Align alignX = Align::Mid, alignY = Align::Mid;
    bool meet = true;
    uint32_t line = 0;
};

std::string_view trimmed(std::string_view s) {
    const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (!s.empty() && space(s.front())) s.remove_prefix(1);
    while (!s.empty() && space(s.back())) s.remove_suffix(1);
    return s;
}

// libsvg's parse_length: a number and an optional unit; Undefined otherwise.
Length lengthOf(std::string_view text) {
    text = trimmed(text);
    size_t split = text.size();
    while (split > 0 &&
           (std::isalpha(static_cast<unsigned char>(text[split - 1])) || text[split - 1] == '%'))
        --split;
    const auto number = detail::wholeNumber(trimmed(text.substr(0, split)));
    if (!number) return {};
    const std::string_view u = text.substr(split);
    static const std::pair<std::string_view, Unit> units[] = {
        {"", Unit::None}, {"%", Unit::Percent}, {"em", Unit::Em}, {"ex", Unit::Ex},
        {"px", Unit::Px}, {"in", Unit::In},     {"cm", Unit::Cm}, {"mm", Unit::Mm},
        {"pt", Unit::Pt}, {"pc", Unit::Pc}};
    for (const auto& [name, unit] : units)
        if (u == name) return {*number, unit};
    return {};
}

// import_svg.cc's to_mm.
double toMm(const Length& length, double viewBox, bool viewBoxValid, double dpi) {
    constexpr double kInch = 25.4;
    switch (length.unit) {
        case Unit::None:
            return kInch * length.number / dpi;
        case Unit::Px:
            return kInch * length.number / 96.0;
        case Unit::Pt:
            return kInch * length.number / 72.0;
        case Unit::Pc:
            return kInch * length.number / 6.0;
        case Unit::In:
            return kInch * length.number;
        case Unit::Cm:
            return 10 * length.number;
        case Unit::Mm:
            return length.number;
        case Unit::Undefined:
            return viewBoxValid ? kInch * viewBox / dpi : 0.0;
        default:
            return viewBoxValid ? viewBox : 0.0;  // em, ex, %
    }
}

// import_svg.cc's calc_alignment.
double alignment(Align a, double pageMm, double scale, double viewBox) {
    switch (a) {
        case Align::Mid:
            return pageMm / 2.0 - scale * viewBox / 2.0;
        case Align::Max:
            return pageMm - scale * viewBox;
        default:
            return 0.0;
    }
}

// libsvg's parse_alignment: [defer] <align> [meet|slice]; anything else is the default
// (xMidYMid meet).
void readAlignment(std::string_view text, Page& page) {
    std::istringstream in{std::string(text)};
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    size_t k = !words.empty() && words[0] == "defer" ? 1 : 0;
    if (k >= words.size() || words.size() > k + 2) return;
    static const std::pair<std::string_view, std::pair<Align, Align>> aligns[] = {
        {"none", {Align::None, Align::None}},   {"xMinYMin", {Align::Min, Align::Min}},
        {"xMidYMin", {Align::Mid, Align::Min}}, {"xMaxYMin", {Align::Max, Align::Min}},
        {"xMinYMid", {Align::Min, Align::Mid}}, {"xMidYMid", {Align::Mid, Align::Mid}},
        {"xMaxYMid", {Align::Max, Align::Mid}}, {"xMinYMax", {Align::Min, Align::Max}},
        {"xMidYMax", {Align::Mid, Align::Max}}, {"xMaxYMax", {Align::Max, Align::Max}}};
    const auto found = std::find_if(std::begin(aligns), std::end(aligns),
                                    [&](const auto& a) { return a.first == words[k]; });
    if (found == std::end(aligns)) return;
    if (k + 1 < words.size() && words[k + 1] != "meet" && words[k + 1] != "slice") return;
    page.alignX = found->second.first;
    page.alignY = found->second.second;
    page.meet = k + 1 >= words.size() || words[k + 1] == "meet";
}

// A box holding the segment tightly: the ends and the points where x or y turns.
void addTightBounds(const Segment2& s, Bounds2& b) {
    b.add(s.start());
    b.add(s.finish());
    auto addAt = [&](double u) {
        if (u > 0.0 && u < 1.0) b.add(s.at(u));
    };
    for (int k = 0; k < 2; ++k) {
        switch (s.kind) {
            case Segment2::Kind::Line:
                break;
            case Segment2::Kind::Quadratic: {
                const double den = s.p[0][k] - 2 * s.p[1][k] + s.p[2][k];
                if (den != 0.0) addAt((s.p[0][k] - s.p[1][k]) / den);
                break;
            }
            case Segment2::Kind::Cubic: {
                // B'(u)/3 = a u^2 + b u + c
                const double p0 = s.p[0][k], p1 = s.p[1][k], p2 = s.p[2][k], p3 = s.p[3][k];
                const double a = -p0 + 3 * p1 - 3 * p2 + p3, bb = 2 * (p0 - 2 * p1 + p2),
                             c = p1 - p0;
                if (a == 0.0) {
                    if (bb != 0.0) addAt(-c / bb);
                } else {
                    const double disc = bb * bb - 4 * a * c;
                    if (disc >= 0.0) {
                        const double r = std::sqrt(disc);
                        addAt((-bb + r) / (2 * a));
                        addAt((-bb - r) / (2 * a));
                    }
                }
                break;
            }
            case Segment2::Kind::Arc: {
                // x(th) = c + A cos th + B sin th turns at th = atan2(B, A) + j pi.
                const double th = std::atan2(s.p[3][k], s.p[2][k]);
                const double span = s.th1 - s.th0;
                if (span <= 0.0) break;
                for (int j = -4; j <= 4; ++j) addAt((th + j * std::numbers::pi - s.th0) / span);
                break;
            }
        }
    }
}

class Reader {
public:
    explicit Reader(const SvgOptions& options)
        : options_(options), sink_(options.faceted, options.maxSegments) {}

    SvgReadResult run(std::string_view text) {
        SvgReadResult result;
        xml::XMLDocument doc(true, xml::PRESERVE_WHITESPACE);
        if (doc.Parse(text.data(), text.size()) != xml::XML_SUCCESS) {
            result.error = "malformed XML: " + xmlError(doc.ErrorID());
            result.line = uint32_t(std::max(doc.ErrorLineNum(), 0));
            return result;
        }
        for (const xml::XMLElement* e = doc.FirstChildElement(); e && !error_;
             e = e->NextSiblingElement())
            visit(e, Affine());
        if (error_) {
            result.error = *error_;
            result.line = errorLine_;
            return result;
        }
        result.drawing = finish();
        return result;
    }

private:
    static std::string xmlError(xml::XMLError id) {
        switch (id) {
            case xml::XML_ERROR_EMPTY_DOCUMENT:
                return "the file has no element";
            case xml::XML_ERROR_MISMATCHED_ELEMENT:
                return "the element here is closed by the end tag of another";
            case xml::XML_ERROR_PARSING_ELEMENT:
                return "an element is not well-formed";
            case xml::XML_ERROR_PARSING_ATTRIBUTE:
                return "an attribute is not well-formed";
            case xml::XML_ERROR_PARSING_TEXT:
                return "text is not well-formed";
            case xml::XML_ERROR_PARSING_CDATA:
                return "a CDATA section is not closed";
            case xml::XML_ERROR_PARSING_COMMENT:
                return "a comment is not closed";
            case xml::XML_ERROR_PARSING_DECLARATION:
                return "a declaration is not well-formed";
            case xml::XML_ERROR_PARSING_UNKNOWN:
                return "a <!...> section is not well-formed";
            case xml::XML_ELEMENT_DEPTH_EXCEEDED:
                return "elements are nested more than " +
                       std::to_string(TINYXML2_MAX_ELEMENT_DEPTH) + " deep";
            default:
                return xml::XMLDocument::ErrorIDToName(id);
        }
    }

    void fail(const xml::XMLElement* e, std::string message) {
        if (error_) return;
        error_ = std::move(message);
        errorLine_ = uint32_t(std::max(e->GetLineNum(), 0));
    }
    // Warnings one by one up to kMaxWarnings, then only counted (a file can have a
    // misread attribute on every element).
    void warn(const xml::XMLElement* e, std::string message) {
        if (++warnings_ > kMaxWarnings) return;
        drawing_.warnings.push_back({uint32_t(std::max(e->GetLineNum(), 0)), std::move(message)});
    }
    void warnOnce(const xml::XMLElement* e, bool& done, std::string message) {
        if (!done) warn(e, std::move(message));
        done = true;
    }

    // libsvg's parse_double of an attribute: the number, 0 when missing; a length with a unit
    // or other text is 0 too (with a warning), a number beyond 2^40 an error.
    double number(const xml::XMLElement* e, const char* name) {
        const char* text = e->Attribute(name);
        if (!text || !*text) return 0.0;
        std::vector<double> list;
        const auto bad = detail::numberList(text, list);
        if (!bad && list.size() == 1) return list[0];
        if (bad && bad->find("beyond") != std::string::npos) {
            fail(e, std::string(e->Name()) + " " + name + ": " + *bad);
            return 0.0;
        }
        warn(e, std::string(e->Name()) + " " + name + "=\"" + text +
                    "\" is not a plain number; it is read as 0, as OpenSCAD 2021 reads it");
        return 0.0;
    }

    // libsvg's shape::get_style: the value of `name` in style="a:b;c:d" (no spaces trimmed).
    static std::string styleOf(const xml::XMLElement* e, std::string_view name) {
        const char* style = e->Attribute("style");
        if (!style) return {};
        std::string_view s(style);
        while (true) {
            const size_t end = s.find(';');
            const std::string_view item = s.substr(0, end);
            const size_t colon = item.find(':');
            if (colon != std::string_view::npos &&
                item.find(':', colon + 1) == std::string_view::npos &&
                item.substr(0, colon) == name)
                return std::string(item.substr(colon + 1));
            if (end == std::string_view::npos) return {};
            s.remove_prefix(end + 1);
        }
    }

    static std::string property(const xml::XMLElement* e, const char* name) {
        const char* attr = e->Attribute(name);
        return attr && *attr ? std::string(attr) : styleOf(e, name);
    }

    // libsvg's stroke: the element's own stroke-width, -linejoin and -linecap (attribute, else
    // style), never inherited.
    detail::Stroke strokeOf(const xml::XMLElement* e) {
        detail::Stroke stroke;
        const std::string width = property(e, "stroke-width");
        const auto w = detail::wholeNumber(width);
        if (!width.empty() && !w)
            warn(e, "stroke-width \"" + width +
                        "\" is not a plain number; it is read as 1, as OpenSCAD 2021 reads it");
        stroke.width = w && *w >= 0.01 ? *w : 1.0;
        const std::string join = property(e, "stroke-linejoin");
        stroke.join = join == "bevel"   ? detail::StrokeJoin::Square
                      : join == "round" ? detail::StrokeJoin::Round
                                        : detail::StrokeJoin::Miter;
        const std::string cap = property(e, "stroke-linecap");
        stroke.cap = cap == "butt"    ? detail::StrokeCap::Butt
                     : cap == "round" ? detail::StrokeCap::Round
                                      : detail::StrokeCap::Square;
        return stroke;
    }

    // The transform attribute: matrix, translate, scale, rotate, skewX, skewY, applied right
    // to left. A function with the wrong number of arguments is skipped, as libsvg skips it.
    std::optional<Affine> transformOf(const xml::XMLElement* e) {
        const char* attr = e->Attribute("transform");
        Affine total;
        if (!attr) return total;
        const std::string_view t(attr);
        size_t pos = 0;
        auto skip = [&] {
            while (pos < t.size() &&
                   (std::isspace(static_cast<unsigned char>(t[pos])) || t[pos] == ','))
                ++pos;
        };
        for (skip(); pos < t.size(); skip()) {
            const size_t open = t.find('(', pos), close = t.find(')', pos);
            if (open == std::string_view::npos || close == std::string_view::npos || close < open) {
                fail(e, "transform \"" + std::string(t) + "\": expected name(numbers)");
                return std::nullopt;
            }
            const std::string_view name = trimmed(t.substr(pos, open - pos));
            std::vector<double> a;
            if (const auto bad = detail::numberList(t.substr(open + 1, close - open - 1), a)) {
                fail(e, "transform \"" + std::string(t) + "\": " + *bad);
                return std::nullopt;
            }
            pos = close + 1;
            const size_t n = a.size();
            std::optional<Affine> step;
            if (name == "matrix") {
                if (n == 6) step = matrixOf(a[0], a[1], a[2], a[3], a[4], a[5]);
            } else if (name == "translate") {
                if (n == 1 || n == 2) step = matrixOf(1, 0, 0, 1, a[0], n == 2 ? a[1] : 0);
            } else if (name == "scale") {
                if (n == 1 || n == 2) step = matrixOf(a[0], 0, 0, n == 2 ? a[1] : a[0], 0, 0);
            } else if (name == "rotate") {
                if (n == 1 || n == 3) {
                    const double c = openscadCosDegrees(a[0]), s = openscadSinDegrees(a[0]);
                    step = matrixOf(c, s, -s, c, 0, 0);
                    if (n == 3)
                        step = matrixOf(1, 0, 0, 1, a[1], a[2])
                                   .then(*step)
                                   .then(matrixOf(1, 0, 0, 1, -a[1], -a[2]));
                }
            } else if (name == "skewX") {
                if (n == 1) step = matrixOf(1, 0, openscadTanDegrees(a[0]), 1, 0, 0);
            } else if (name == "skewY") {
                if (n == 1) step = matrixOf(1, openscadTanDegrees(a[0]), 0, 1, 0, 0);
            } else {
                fail(e, "transform \"" + std::string(t) + "\": unknown function '" +
                            std::string(name) + "'");
                return std::nullopt;
            }
            if (!step) {
                warn(e, "transform " + std::string(name) + "() with " + std::to_string(n) +
                            " arguments is skipped, as OpenSCAD 2021 skips it");
                continue;
            }
            total = total.then(*step);
        }
        if (!total.finite()) {
            fail(e, "transform \"" + std::string(t) + "\" is not finite");
            return std::nullopt;
        }
        return total;
    }

    void readPage(const xml::XMLElement* e) {
        Page page;
        page.line = uint32_t(std::max(e->GetLineNum(), 0));
        if (const char* w = e->Attribute("width")) page.width = lengthOf(w);
        if (const char* h = e->Attribute("height")) page.height = lengthOf(h);
        if (const char* vb = e->Attribute("viewBox")) {
            std::vector<double> v;
            if (!detail::numberList(vb, v) && v.size() == 4 && v[2] >= 0 && v[3] >= 0) {
                page.viewBoxValid = true;
                std::copy(v.begin(), v.end(), page.viewBox);
            }
        }
        if (const char* a = e->Attribute("preserveAspectRatio")) readAlignment(a, page);
        page_ = page;  // the last <svg> is the page, as in import_svg
    }

    void visit(const xml::XMLElement* e, const Affine& parent) {
        const std::string_view name = e->Name();
        if (name == "defs") return;
        const bool container = name == "g" || name == "text" || name == "tspan";
        Affine here = parent;
        if (name == "svg") {
            readPage(e);
        } else if (container || isShape(name)) {
            const auto own = transformOf(e);
            if (!own) return;
            here = parent.then(*own);
        }
        if (name == "text") warnOnce(e, warnedText_, "SVG text is not drawn (nor by OpenSCAD)");
        if (name == "use" || name == "image")
            warnOnce(e, warnedUse_,
                     "<" + std::string(name) + "> is not drawn (nor by OpenSCAD 2021)");
        if (isShape(name)) {
            shape(e, name, here);
            if (error_) return;
        }
        // A shape's children (libsvg pushes only containers) see the shape's parent's transform.
        const Affine& inner = isShape(name) ? parent : here;
        for (const xml::XMLElement* c = e->FirstChildElement(); c && !error_;
             c = c->NextSiblingElement())
            visit(c, inner);
    }

    static bool isShape(std::string_view n) {
        return n == "path" || n == "rect" || n == "circle" || n == "ellipse" || n == "line" ||
               n == "polyline" || n == "polygon";
    }

    void shape(const xml::XMLElement* e, std::string_view name, const Affine& transform) {
        const detail::Stroke stroke = strokeOf(e);
        if (name == "path") {
            const char* d = e->Attribute("d");
            if (auto bad = detail::pathShape(d ? d : "", stroke, sink_))
                return fail(e, "path d: " + *bad);
        } else if (name == "rect") {
            detail::rectShape(number(e, "x"), number(e, "y"), number(e, "width"),
                              number(e, "height"), number(e, "rx"), number(e, "ry"), stroke, sink_);
        } else if (name == "circle") {
            const double r = number(e, "r");
            detail::ellipseShape(number(e, "cx"), number(e, "cy"), r, r, sink_);
        } else if (name == "ellipse") {
            detail::ellipseShape(number(e, "cx"), number(e, "cy"), number(e, "rx"), number(e, "ry"),
                                 sink_);
        } else if (name == "line") {
            sink_.stroke(
                {Vec2(number(e, "x1"), number(e, "y1")), Vec2(number(e, "x2"), number(e, "y2"))},
                stroke);
        } else {  // polyline, polygon
            const char* text = e->Attribute("points");
            std::vector<double> v;
            if (auto bad = detail::numberList(text ? text : "", v))
                return fail(e, std::string(name) + " points: " + *bad);
            if (v.size() % 2 != 0)
                warn(e, std::string(name) +
                            " points has an odd count of numbers; the last is dropped, as "
                            "OpenSCAD 2021 drops it");
            std::vector<Vec2> points;
            for (size_t k = 0; k + 1 < v.size(); k += 2) points.emplace_back(v[k], v[k + 1]);
            if (name == "polygon")
                sink_.polygon(points);
            else
                sink_.stroke(points, stroke);
        }
        for (std::string& note : sink_.takeNotes()) warn(e, std::move(note));
        if (error_) return;
        if (sink_.error()) return fail(e, *sink_.error());
        std::vector<Segment2> segments = sink_.take();
        if (segments.empty()) return;
        const double det =
            transform.m[0][0] * transform.m[1][1] - transform.m[1][0] * transform.m[0][1];
        if (det == 0.0) return;  // a shape collapsed to a line or point has no area
        for (Segment2& s : segments) {
            s = s.mapped(transform.m, transform.t);
            addTightBounds(s, bounds_);
        }
        shapes_.push_back(std::move(segments));
    }

    // import_svg: the page map, then one outline per shape.
    SvgDrawing finish() {
        const Page& p = page_;
        const double dpi = options_.dpi;
        const double widthMm = toMm(p.width, p.viewBox[2], p.viewBoxValid, dpi);
        const double heightMm = toMm(p.height, p.viewBox[3], p.viewBoxValid, dpi);
        Vec2 scale(1.0), align(0.0), origin(0.0);
        if (p.viewBoxValid) {
            if (p.viewBox[2] == 0.0 || p.viewBox[3] == 0.0) {
                drawing_.warnings.push_back(
                    {p.line, "the viewBox has no area; nothing is drawn (as SVG draws nothing)"});
                shapes_.clear();
            } else {
                origin = Vec2(p.viewBox[0], p.viewBox[1]);
                scale = Vec2(widthMm / p.viewBox[2], heightMm / p.viewBox[3]);
                if (p.alignX != Align::None) {
                    const double s =
                        p.meet ? std::min(scale.x, scale.y) : std::max(scale.x, scale.y);
                    scale = Vec2(s);
                    align = Vec2(alignment(p.alignX, widthMm, s, p.viewBox[2]),
                                 alignment(p.alignY, heightMm, s, p.viewBox[3]));
                }
            }
        }
        // import_svg centres the box of (scale x, scale y), before the viewBox origin and
        // the flip are applied.
        const bool center = options_.center && !bounds_.empty();
        const double cx = center ? scale.x * (bounds_.lo.x + bounds_.hi.x) / 2 : -align.x;
        const double cy = center ? scale.y * (bounds_.lo.y + bounds_.hi.y) / 2 : heightMm - align.y;
        Affine page;
        page.m = glm::dmat2(scale.x, 0.0, 0.0, -scale.y);
        page.t = Vec2(-scale.x * origin.x - cx, -scale.y * origin.y + cy);
        if (!page.finite() || scale.x * scale.y == 0.0) shapes_.clear();
        for (std::vector<Segment2>& segments : shapes_) {
            csg::Outline outline;
            outline.rule = csg::FillRule::EvenOdd;
            outline.segments.reserve(segments.size());
            bool finite = true;
            for (const Segment2& s : segments) {
                outline.segments.push_back(s.mapped(page.m, page.t));
                for (const Vec2& q : outline.segments.back().p)
                    finite = finite && std::isfinite(q.x) && std::isfinite(q.y);
            }
            if (!finite) {
                drawing_.warnings.push_back(
                    {0, "a shape's coordinates overflow under its transforms; it is dropped"});
                continue;
            }
            drawing_.shapes.push_back(std::move(outline));
        }
        if (warnings_ > kMaxWarnings)
            drawing_.warnings.push_back(
                {0, "... and " + std::to_string(warnings_ - kMaxWarnings) + " more warnings"});
        drawing_.segments = sink_.total();
        return std::move(drawing_);
    }

    const SvgOptions& options_;
    detail::ShapeSink sink_;
    SvgDrawing drawing_;
    Page page_;
    std::vector<std::vector<Segment2>> shapes_;  // user units, under their transforms
    Bounds2 bounds_;
    std::optional<std::string> error_;
    uint32_t errorLine_ = 0;
    bool warnedText_ = false, warnedUse_ = false;
    uint64_t warnings_ = 0;
    static constexpr uint64_t kMaxWarnings = 20;
};

}  // namespace

SvgReadResult readSvg(std::string_view text, const SvgOptions& options) {
    return Reader(options).run(text);
}

SvgReadResult readSvgFile(const std::filesystem::path& file, const SvgOptions& options) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        SvgReadResult r;
        r.error = "cannot open the SVG file";
        r.unreadable = true;
        return r;
    }
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return readSvg(bytes.str(), options);
}

}  // namespace io
