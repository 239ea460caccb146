// The DXF reader: group code / value pairs interpreted as OpenSCAD 2021's DxfData::DxfData
// does (src/dxfdata.cc), statement for statement where the result depends on it: which
// coordinates the origin and scale apply to, the defaults of absent values, how an entity is
// drawn when the next group 0 ends it, which ends snap where. Its quirks are kept because
// parts were made against them: an ELLIPSE's major axis (a vector) is moved by the origin
// and its ratio scaled; an INSERT ignores its block's base point; block lines are filed in
// the chaining grid (DxfGrid.h). Where OpenSCAD warns about malformed input and reads on in a
// state it did not mean to be in, this reader stops with an error and the line.
#include "io/DxfFile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <unordered_map>

#include "io/Degrees.h"
#include "io/DxfGrid.h"
#include "primitives/base/ReadFile.h"

namespace io {

namespace {

using csg::Segment2;
using csg::Vec2;
using detail::DxfGrid;

// Beyond this a coordinate's grid node number (x * 1024) would not be an exact integer.
constexpr double kMaxCoordinate = 0x1p40;
// More turns than this added one at a time to an ARC's end angle: computed in one step.
constexpr double kMaxAngleSteps = 1e6;

struct ReadError {
    uint32_t line;
    std::string message;
};

[[noreturn]] void fail(uint32_t line, std::string message) {
    throw ReadError{line, std::move(message)};
}

// What boost::trim removes (the "C" locale's isspace).
bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
    return s;
}

// The file's lines, ended by "\n", "\r\n" or a lone "\r", each trimmed, numbered from 1.
class LineReader {
public:
    explicit LineReader(std::string_view text) : text_(text) {
        if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);  // a UTF-8 mark
    }
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        size_t end = pos_;
        while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
        line = trimmed(text_.substr(pos_, end - pos_));
        if (end < text_.size())
            end += text_[end] == '\r' && end + 1 < text_.size() && text_[end + 1] == '\n' ? 2 : 1;
        pos_ = end;
        ++number_;
        return true;
    }
    // Whether only blank lines are left.
    bool restIsBlank() const { return trimmed(text_.substr(pos_)).empty(); }
    uint32_t number() const { return number_; }

private:
    std::string_view text_;
    size_t pos_ = 0;
    uint32_t number_ = 0;
};

double parseNumber(std::string_view text, uint32_t line, int code) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value))
        fail(line, "group " + std::to_string(code) + " needs a finite number, got '" +
                       std::string(text.substr(0, 40)) + "'");
    return value;
}

int parseInteger(std::string_view text, uint32_t line, int code) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    int value = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size())
        fail(line, "group " + std::to_string(code) + " needs an integer, got '" +
                       std::string(text.substr(0, 40)) + "'");
    return value;
}

// The fields of the entity being read, named after what OpenSCAD stores them in (its parser
// files a group code in the same field whatever the entity: 40 is a CIRCLE's radius and an
// ELLIPSE's axis ratio, 41/42 an ELLIPSE's angles and an INSERT's scale).
struct Entity {
    std::string mode;  // the entity type, from the group 0 that began it
    uint32_t line = 0;
    std::string layer, name, iddata;
    int dimtype = 0;  // group 70: LWPOLYLINE flags, DIMENSION type, vertex flags
    Vec2 coords[7]{};
    std::vector<double> xs, ys;  // groups 10 and 11, 20 and 21, in file order
    std::vector<double> bulges;  // group 42 after each group 10 (LWPOLYLINE)
    double radius = 0.0, arcStart = 0.0, arcStop = 0.0;
    double ellipseStart = 0.0, ellipseStop = 0.0;
};

// Where a group's coordinates go: the drawing, or one of the block definitions.
struct Place {
    bool inEntities = false, inBlocks = false;
    std::string layer, block;
};

// A POLYLINE being read through its VERTEX entities (csgray reads these; OpenSCAD does not).
struct Polyline {
    Place place;
    uint32_t line = 0;
    int flags = 0;
    bool mesh = false;  // a polygon or polyface mesh: not a 2-D outline
    std::vector<double> xs, ys, bulges;
};

class Reader {
public:
    explicit Reader(const DxfOptions& options) : options_(options) {}

    void group(int code, std::string_view value, uint32_t line);
    // Ends the last entity; true when reading stops (at EOF).
    bool atEof() const { return entity_.mode == "EOF"; }
    DxfDrawing finish();

private:
    double coordinate(double v, double origin, bool shifted) const {
        if (place_.inBlocks) return v;
        return shifted ? (v - origin) * options_.scale : v * options_.scale;
    }
    bool layerWanted(const std::string& layer) const {
        return options_.layer.empty() || options_.layer == layer;
    }
    // Whether what is emitted at `at` is kept: drawing entities of the layer, block entities.
    bool drawn(const Place& at) const {
        return at.inBlocks || (at.inEntities && layerWanted(at.layer));
    }
    void endEntity();
    void needPoints(size_t n, const char* what) const;

    // ---- drawing (ADD_LINE) ----
    // An edge from p1 to p2 (a line, or the arc given), filed as OpenSCAD files a line.
    void emit(const Place& at, Vec2 p1, Vec2 p2, const Segment2* arc = nullptr);
    void countEdges(uint64_t n) const;
    void emitCircle(const Place& at, Vec2 center, double r);
    void emitArc(const Place& at, Vec2 center, double r, double startDeg, double stopDeg);
    void emitEllipse(const Place& at);
    void emitInsert(const Place& at);
    // LWPOLYLINE and POLYLINE: the vertices in order, each with the bulge of the edge after it.
    void emitPolyline(const Place& at, const std::vector<double>& xs, const std::vector<double>& ys,
                      const std::vector<double>& bulges, bool closed);
    void emitBulge(const Place& at, Vec2 p, Vec2 q, double bulge);
    void finishPolyline();
    void unsupported(const std::string& mode);

    const DxfOptions& options_;
    DxfDrawing drawing_;
    DxfGrid grid_;
    std::vector<std::array<DxfGrid::Cell*, 2>> ends_;  // the cells of each edge's ends
    std::unordered_map<std::string, std::vector<Segment2>> blocks_;
    uint64_t blockEdges_ = 0;
    Place place_;  // the section and block being read
    Entity entity_;
    std::optional<Polyline> polyline_;
    bool warnedBulges_ = false;
};

void Reader::group(int code, std::string_view value, uint32_t line) {
    auto number = [&] { return parseNumber(value, line, code); };
    if (code >= 10 && code <= 16) {
        const bool shifted = code != 11 && code != 12 && code != 16;
        entity_.coords[code - 10].x = coordinate(number(), options_.origin.x, shifted);
    }
    if (code >= 20 && code <= 26) {
        const bool shifted = code != 21 && code != 22 && code != 26;
        entity_.coords[code - 20].y = coordinate(number(), options_.origin.y, shifted);
    }
    switch (code) {
        case 0:
            endEntity();
            entity_ = Entity();
            entity_.mode = value;
            entity_.line = line;
            if (entity_.mode == "INSERT") entity_.ellipseStart = entity_.ellipseStop = 1.0;
            break;
        case 1:
            entity_.name = value;
            break;
        case 2:
            entity_.iddata = value;
            break;
        case 8:
            entity_.layer = value;
            break;
        case 10:
        case 11:
            entity_.xs.push_back(coordinate(number(), options_.origin.x, true));
            if (code == 10) entity_.bulges.resize(entity_.xs.size(), 0.0);
            break;
        case 20:
        case 21:
            entity_.ys.push_back(coordinate(number(), options_.origin.y, true));
            break;
        case 40:
            entity_.radius = number();
            if (!place_.inBlocks) entity_.radius *= options_.scale;
            break;
        case 41:
            entity_.ellipseStart = number();
            break;
        case 42:
            entity_.ellipseStop = number();
            if (!entity_.bulges.empty()) entity_.bulges.back() = entity_.ellipseStop;
            break;
        case 50:
            entity_.arcStart = number();
            break;
        case 51:
            entity_.arcStop = number();
            break;
        case 70:
            entity_.dimtype = parseInteger(value, line, code);
            break;
        default:
            break;
    }
}

void Reader::needPoints(size_t n, const char* what) const {
    if (entity_.xs.size() < n || entity_.ys.size() < n)
        fail(entity_.line, entity_.mode + " needs " + what + " (" + std::to_string(n) +
                               " x and y coordinates, groups 10/20" + (n > 1 ? ", 11/21" : "") +
                               "); it has " + std::to_string(entity_.xs.size()) + " and " +
                               std::to_string(entity_.ys.size()));
}

void Reader::endEntity() {
    const Entity& e = entity_;
    const std::string& mode = e.mode;
    Place at = place_;
    at.layer = e.layer;
    const bool polylinePart = !options_.only2021 && (mode == "VERTEX" || mode == "SEQEND");
    if (polyline_ && !polylinePart) finishPolyline();  // a POLYLINE without its SEQEND
    if (mode == "SECTION") {
        place_.inEntities = e.iddata == "ENTITIES";
        place_.inBlocks = e.iddata == "BLOCKS";
    } else if (mode == "LINE") {
        needPoints(2, "a start and an end");
        emit(at, {e.xs[0], e.ys[0]}, {e.xs[1], e.ys[1]});
    } else if (mode == "LWPOLYLINE") {
        if (e.xs.size() != e.ys.size())
            fail(e.line, "LWPOLYLINE has " + std::to_string(e.xs.size()) + " x but " +
                             std::to_string(e.ys.size()) + " y coordinates");
        emitPolyline(at, e.xs, e.ys, e.bulges, (e.dimtype & 1) != 0);
    } else if (mode == "CIRCLE") {
        needPoints(1, "a centre");
        emitCircle(at, {e.xs[0], e.ys[0]}, e.radius);
    } else if (mode == "ARC") {
        needPoints(1, "a centre");
        emitArc(at, {e.xs[0], e.ys[0]}, e.radius, e.arcStart, e.arcStop);
    } else if (mode == "ELLIPSE") {
        needPoints(2, "a centre and a major axis");
        emitEllipse(at);
    } else if (mode == "INSERT") {
        needPoints(1, "an insertion point");
        emitInsert(at);
    } else if (mode == "DIMENSION" && layerWanted(e.layer)) {
        DxfDimension d;
        d.type = e.dimtype;
        std::copy(std::begin(e.coords), std::end(e.coords), std::begin(d.coords));
        d.angle = e.arcStart;
        d.length = e.radius;
        d.name = e.name;
        drawing_.dimensions.push_back(std::move(d));
    } else if (mode == "BLOCK") {
        place_.block = e.iddata;
    } else if (mode == "ENDBLK") {
        place_.block.clear();
    } else if (mode == "ENDSEC" || mode.empty()) {
    } else if (!options_.only2021 && mode == "POLYLINE") {
        polyline_ = Polyline{at, e.line, e.dimtype, (e.dimtype & (16 | 64)) != 0, {}, {}, {}};
    } else if (polylinePart && polyline_) {
        if (mode == "SEQEND") {
            finishPolyline();
        } else if ((e.dimtype & 16) == 0) {  // not a spline's frame control point
            needPoints(1, "a position");
            polyline_->xs.push_back(e.xs[0]);
            polyline_->ys.push_back(e.ys[0]);
            polyline_->bulges.push_back(e.bulges.empty() ? 0.0 : e.bulges[0]);
        }
    } else if (drawn(at)) {
        unsupported(mode);
    }
}

void Reader::unsupported(const std::string& mode) {
    for (auto& [name, count] : drawing_.unsupported)
        if (name == mode) return void(++count);
    drawing_.unsupported.emplace_back(mode, 1);
}

void Reader::countEdges(uint64_t n) const {
    if (n > options_.maxEdges || drawing_.edges.size() + blockEdges_ > options_.maxEdges - n)
        fail(entity_.line, "the drawing needs more than " + std::to_string(options_.maxEdges) +
                               " edges (" + entity_.mode + " with " + std::to_string(n) + ")");
}

void Reader::emit(const Place& at, Vec2 p1, Vec2 p2, const Segment2* arc) {
    if (!drawn(at)) return;
    auto far = [](Vec2 p) {
        return !(std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate);
    };
    // An arc's centre and axes too: a huge or infinite ellipse has ends in range only by luck.
    if (far(p1) || far(p2) || (arc && (far(arc->p[1]) || far(arc->p[2]) || far(arc->p[3]))))
        fail(entity_.line, entity_.mode + " reaches beyond +-2^40 (after origin and scale)");
    countEdges(1);
    DxfGrid::Cell& c1 = grid_.align(p1);
    DxfGrid::Cell& c2 = grid_.align(p2);
    // OpenSCAD files the ends of a block's lines too, under the next drawing line's number.
    c1.push_back(int64_t(drawing_.edges.size()));
    c2.push_back(int64_t(drawing_.edges.size()));
    Segment2 s = Segment2::line(p1, p2);
    if (arc) {
        s = *arc;
        s.p[0] = p1;
        s.end = p2;
    }
    if (at.inEntities) {
        drawing_.edges.push_back(s);
        ends_.push_back({&c1, &c2});
    }
    if (at.inBlocks && !at.block.empty()) {
        blocks_[at.block].push_back(s);
        ++blockEdges_;
    }
}

void Reader::emitCircle(const Place& at, Vec2 center, double r) {
    if (!drawn(at)) return;
    if (!options_.faceted) {
        if (r == 0.0) return;
        const Vec2 start(openscadCosDegrees(0.0) * r + center.x, center.y);
        const Segment2 circle = Segment2::circle(center, r);
        return emit(at, start, start, &circle);
    }
    const int64_t n = fragments(r, options_.fragments);
    countEdges(uint64_t(n));
    auto point = [&](double a) {
        return Vec2(openscadCosDegrees(a) * r + center.x, openscadSinDegrees(a) * r + center.y);
    };
    for (int64_t i = 0; i < n; ++i)
        emit(at, point((360.0 * double(i)) / double(n)),
             point((360.0 * double(i + 1)) / double(n)));
}

// OpenSCAD's `while (start > stop) stop += step`, in one step when it would take many.
double unwound(double start, double stop, double step) {
    if ((start - stop) / step > kMaxAngleSteps) stop += std::ceil((start - stop) / step) * step;
    while (start > stop) stop += step;
    return stop;
}

void Reader::emitArc(const Place& at, Vec2 center, double r, double startDeg, double stopDeg) {
    if (!drawn(at)) return;
    stopDeg = unwound(startDeg, stopDeg, 360.0);
    const double sweep = stopDeg - startDeg;
    auto point = [&](double a) {
        return Vec2(openscadCosDegrees(a) * r + center.x, openscadSinDegrees(a) * r + center.y);
    };
    if (!options_.faceted) {
        if (!(sweep > 0.0) || r == 0.0) return;
        const double turn = std::min(sweep, 360.0);
        const double th0 = startDeg * (csg::kPi / 180.0);
        const Segment2 arc =
            Segment2::arc(center, {r, 0.0}, {0.0, r}, th0, th0 + turn * (csg::kPi / 180.0));
        return emit(at, point(startDeg), point(startDeg + turn), &arc);
    }
    const double chords = std::ceil(double(fragments(r, options_.fragments)) * sweep / 360.0);
    if (!(chords >= 1.0)) return;
    countEdges(chords > 1e18 ? UINT64_MAX : uint64_t(chords));
    const int64_t n = int64_t(chords);
    for (int64_t i = 0; i < n; ++i)
        emit(at, point(startDeg + sweep * double(i) / double(n)),
             point(startDeg + sweep * double(i + 1) / double(n)));
}

void Reader::emitEllipse(const Place& at) {
    if (!drawn(at)) return;
    const Entity& e = entity_;
    const double start = e.ellipseStart;
    const double stop = unwound(start, e.ellipseStop, 2.0 * csg::kPi);
    const Vec2 center(e.xs[0], e.ys[0]);
    const Vec2 ce(e.xs[1], e.ys[1]);  // the major axis (moved by the origin: OpenSCAD's doing)
    const double rMajor = std::sqrt(ce.x * ce.x + ce.y * ce.y);
    double rotation = std::acos(std::clamp(ce.x / rMajor, -1.0, 1.0));
    if (ce.y < 0.0) rotation = 2 * csg::kPi - rotation;
    // OpenSCAD's rotation is NaN then, and so is every point (undefined on its grid).
    if (rMajor == 0.0) return;
    const double rMinor = rMajor * e.radius;
    const double sweep = stop - start;
    const double c = std::cos(rotation), s = std::sin(rotation);
    auto point = [&](double a) {
        const Vec2 q(std::cos(a) * rMajor, std::sin(a) * rMinor);
        return Vec2(c * q.x - s * q.y + center.x, s * q.x + c * q.y + center.y);
    };
    if (!options_.faceted) {
        if (!(sweep > 0.0)) return;
        const double turn = std::min(sweep, 2.0 * csg::kPi);
        const Segment2 arc =
            Segment2::arc(center, Vec2(c, s) * rMajor, Vec2(-s, c) * rMinor, start, start + turn);
        return emit(at, point(start), point(start + turn), &arc);
    }
    const double chords =
        std::ceil(double(fragments(rMajor, options_.fragments)) * sweep / (2 * csg::kPi));
    if (!(chords >= 1.0)) return;
    countEdges(chords > 1e18 ? UINT64_MAX : uint64_t(chords));
    const int64_t n = int64_t(chords);
    Vec2 previous = point(start);
    for (int64_t i = 1; i <= n; ++i) {
        const Vec2 next = point(start + sweep * double(i) / double(n));
        emit(at, previous, next);
        previous = next;
    }
}

void Reader::emitInsert(const Place& at) {
    const Entity& e = entity_;
    if (!drawn(at)) return;
    const auto found = blocks_.find(e.iddata);
    if (found == blocks_.end()) {
        drawing_.warnings.push_back(
            {e.line, "INSERT of block '" + e.iddata +
                         "', which no BLOCK before it defines; it draws nothing"});
        return;
    }
    // OpenSCAD's transform: rotate (group 50) the block's point scaled by groups 41 and 42,
    // times the import's scale, plus the insertion point (which the origin already moved).
    const double a = e.arcStart, sx = e.ellipseStart, sy = e.ellipseStop;
    const double cosA = openscadCosDegrees(a), sinA = openscadSinDegrees(a);
    const double scale = options_.scale;
    const Vec2 insertion(e.xs[0], e.ys[0]);
    auto map = [&](Vec2 p) {
        const double lx = p.x * sx, ly = p.y * sy;
        return Vec2((cosA * lx - sinA * ly) * scale + insertion.x,
                    (sinA * lx + cosA * ly) * scale + insertion.y);
    };
    const glm::dmat2 linear(Vec2(cosA * sx, sinA * sx) * scale,
                            Vec2(-sinA * sy, cosA * sy) * scale);
    // By index: a block may insert into itself (its list then grows as it is read).
    const std::string name = e.iddata;
    const size_t n = found->second.size();
    for (size_t i = 0; i < n; ++i) {
        const Segment2 s = blocks_[name][i];
        if (s.kind == Segment2::Kind::Arc) {
            const Segment2 arc = s.mapped(linear, insertion);
            emit(at, map(s.start()), map(s.finish()), &arc);
        } else {
            emit(at, map(s.start()), map(s.finish()));
        }
    }
}

void Reader::emitPolyline(const Place& at, const std::vector<double>& xs,
                          const std::vector<double>& ys, const std::vector<double>& bulges,
                          bool closed) {
    const size_t n = xs.size();
    auto bulgeAfter = [&](size_t i) { return i < bulges.size() ? bulges[i] : 0.0; };
    for (size_t i = 1; i < n; ++i)
        emitBulge(at, {xs[i - 1], ys[i - 1]}, {xs[i], ys[i]}, bulgeAfter(i - 1));
    if (closed && n > 0) emitBulge(at, {xs[n - 1], ys[n - 1]}, {xs[0], ys[0]}, bulgeAfter(n - 1));
}

void Reader::emitBulge(const Place& at, Vec2 p, Vec2 q, double bulge) {
    // A bulge below 1e-9 bends its edge by less than 1e-9 of its length: straight (and its
    // circle would be too large to compute with).
    if (std::abs(bulge) < 1e-9 || p == q) return emit(at, p, q);
    if (!drawn(at)) return;
    if (options_.only2021) {
        if (!warnedBulges_)
            drawing_.warnings.push_back(
                {entity_.line, entity_.mode +
                                   " bulges (arcs) are read as straight lines, as OpenSCAD 2021 "
                                   "reads them"});
        warnedBulges_ = true;
        return emit(at, p, q);
    }
    // The arc from p to q turning by 4 atan(bulge) (counter-clockwise when positive): its
    // centre lies off the chord's midpoint by chord (1 - b^2) / (4 b) along the chord's left
    // normal, its radius is chord (1 + b^2) / (4 |b|).
    const Vec2 chord = q - p;
    const Vec2 center =
        0.5 * (p + q) + Vec2(-chord.y, chord.x) * ((1.0 - bulge * bulge) / (4.0 * bulge));
    const double r = glm::length(chord) * (1.0 + bulge * bulge) / (4.0 * std::abs(bulge));
    const double turn = 4.0 * std::atan(std::abs(bulge));  // radians, in (0, 2 pi)
    // Counter-clockwise from `from` to `to`.
    const Vec2 from = bulge > 0.0 ? p : q, to = bulge > 0.0 ? q : p;
    const double th0 = std::atan2(from.y - center.y, from.x - center.x);
    if (!options_.faceted) {
        const Segment2 arc = Segment2::arc(center, {r, 0.0}, {0.0, r}, th0, th0 + turn);
        return emit(at, from, to, &arc);
    }
    // OpenSCAD's chords of an ARC with this centre, radius and angles, ending exactly at p, q.
    const double startDeg = th0 * (180.0 / csg::kPi), sweepDeg = turn * (180.0 / csg::kPi);
    const int64_t n = std::max<int64_t>(
        1, int64_t(std::ceil(double(fragments(r, options_.fragments)) * sweepDeg / 360.0)));
    countEdges(uint64_t(n));
    Vec2 previous = from;
    for (int64_t i = 1; i <= n; ++i) {
        const double a = startDeg + sweepDeg * double(i) / double(n);
        const Vec2 next = i == n ? to
                                 : Vec2(openscadCosDegrees(a) * r + center.x,
                                        openscadSinDegrees(a) * r + center.y);
        emit(at, previous, next);
        previous = next;
    }
}

void Reader::finishPolyline() {
    Polyline pl = std::move(*polyline_);
    polyline_.reset();
    if (pl.mesh) {
        if (drawn(pl.place)) unsupported("POLYLINE (polygon or polyface mesh)");
        return;
    }
    const uint32_t line = entity_.line;
    entity_.line = pl.line;  // errors name the POLYLINE
    emitPolyline(pl.place, pl.xs, pl.ys, pl.bulges, (pl.flags & 1) != 0);
    entity_.line = line;
}

DxfDrawing Reader::finish() {
    if (!atEof()) endEntity();
    if (polyline_) finishPolyline();
    if (auto error = detail::chainPaths(drawing_, grid_, ends_)) fail(0, *error);
    return std::move(drawing_);
}

}  // namespace

DxfReadResult readDxf(std::string_view text, const DxfOptions& options) {
    DxfReadResult result;
    try {
        if (text.substr(0, 18) == "AutoCAD Binary DXF")
            fail(1, "a binary DXF file (csgray, like OpenSCAD, reads ASCII DXF)");
        LineReader lines(text);
        Reader reader(options);
        std::string_view codeText, value;
        bool any = false;
        while (!reader.atEof() && lines.next(codeText)) {
            const uint32_t codeLine = lines.number();
            if (codeText.empty() && lines.restIsBlank()) break;
            int code = 0;
            const auto [ptr, ec] =
                std::from_chars(codeText.data() + (codeText.starts_with('+') ? 1 : 0),
                                codeText.data() + codeText.size(), code);
            if (ec != std::errc() || ptr != codeText.data() + codeText.size())
                fail(codeLine, "expected a group code (an integer), got '" +
                                   std::string(codeText.substr(0, 40)) + "'");
            if (!lines.next(value))
                fail(codeLine, "group code " + std::to_string(code) + " has no value line");
            reader.group(code, value, lines.number());
            any = true;
        }
        if (!any) fail(0, "the file is empty (no DXF groups)");
        result.drawing = reader.finish();
    } catch (const ReadError& e) {
        result.error = e.message;
        result.line = e.line;
    }
    return result;
}

DxfReadResult readDxfFile(const std::filesystem::path& file, const DxfOptions& options) {
    std::string bytes;
    if (const csg::ReadFailure failure = csg::readWholeFile(file, bytes);
        failure != csg::ReadFailure::None) {
        DxfReadResult result;
        result.error = failure == csg::ReadFailure::CannotRead ? "cannot read the DXF file"
                                                               : "cannot open the DXF file";
        result.unreadable = true;
        return result;
    }
    return readDxf(bytes, options);
}

}  // namespace io
