// SVG elements into segments: see io/SvgShapes.h, and ../shared/OPENSCAD.md §2 for the
// OpenSCAD 2021 behaviour followed (src/libsvg/).
#include "io/SvgShapes.h"

#include <clipper.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "io/Degrees.h"

namespace io::detail {

namespace {

using csg::Segment2;
using csg::Vec2;
namespace cl = ClipperLib;

constexpr double kPi = std::numbers::pi;
// Numbers of a file beyond this are refused (as DXF coordinates are): far inside the range of
// Clipper's integers at libsvg's scale, so a stroke never overflows it.
constexpr double kMaxNumber = 1099511627776.0;  // 2^40
// libsvg's offset_path works on integers: user units times 10^4, truncated.
constexpr double kStrokeScale = 10000.0;
// Clipper's default arc tolerance (scaled units), which libsvg keeps for round joins and caps.
constexpr double kClipperArcTolerance = 0.25;
// Exact curves are stroked as polylines whose chords stray at most this far (user units) from
// the curve: Clipper's grid is 10^-4, so a finer polyline would change nothing...
constexpr double kStrokeChordTolerance = 1.0e-4;
// ... in at most this many chords a curve (OpenSCAD takes 20): a Bezier 100 units across then
// strays ~10^-3, and a long curvy open path stays within the budget.
constexpr double kMaxStrokeChords = 256;
// Pairs of a stroke's edges that may cross (see crossingCandidates) beyond which the stroke
// is refused: Clipper's union takes time in the number of crossings, and a path that doubles
// back on itself a million times would keep it for hours.
constexpr uint64_t kMaxCrossingCandidates = 100'000'000;
// The same for the sweep (see sweepWork): Clipper's active edge list is walked at every
// scanline, so a long path that winds round many times costs it its length times its turns.
constexpr uint64_t kMaxSweepWork = 100'000'000;
// libsvg's is_open_path: a subpath whose ends are further apart than this is stroked.
constexpr double kOpenDistance = 0.1;

bool isWsp(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f';
}
bool isDigit(char c) {
    return c >= '0' && c <= '9';
}

// SVG's number at pos (sign, digits, fraction, exponent), advancing pos past it; nullopt (pos
// unchanged) when there is none. *bad receives a message for a number out of range.
std::optional<double> scanNumber(std::string_view t, size_t& pos, std::string* bad) {
    size_t i = pos;
    const size_t n = t.size();
    if (i < n && (t[i] == '+' || t[i] == '-')) ++i;
    const size_t digits = i;
    while (i < n && isDigit(t[i])) ++i;
    size_t count = i - digits;
    if (i < n && t[i] == '.') {
        const size_t frac = ++i;
        while (i < n && isDigit(t[i])) ++i;
        count += i - frac;
    }
    if (count == 0) return std::nullopt;
    if (i < n && (t[i] == 'e' || t[i] == 'E')) {
        size_t j = i + 1;
        if (j < n && (t[j] == '+' || t[j] == '-')) ++j;
        const size_t exponent = j;
        while (j < n && isDigit(t[j])) ++j;
        if (j > exponent) i = j;
    }
    const size_t from = t[pos] == '+' ? pos + 1 : pos;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data() + from, t.data() + i, v);
    const std::string text(t.substr(pos, i - pos));
    if (ec == std::errc::result_out_of_range ||
        (ec == std::errc() && !(std::abs(v) <= kMaxNumber))) {
        if (bad) *bad = "the number " + text + " is beyond +-2^40";
        return std::nullopt;
    }
    if (ec != std::errc() || end != t.data() + i) {
        if (bad) *bad = "'" + text + "' is not a number";
        return std::nullopt;
    }
    pos = i;
    return v;
}

// Skips whitespace, at most one comma, and whitespace.
void skipSeparator(std::string_view t, size_t& pos) {
    while (pos < t.size() && isWsp(t[pos])) ++pos;
    if (pos < t.size() && t[pos] == ',') ++pos;
    while (pos < t.size() && isWsp(t[pos])) ++pos;
}

// The pairs of polyline edges whose boxes share a cell of a grid of about n cells: at least
// the pairs that cross. Counting stops past `limit` (the count is then above it), and so does
// the work of filing long edges into many cells.
uint64_t crossingCandidates(const std::vector<Vec2>& points, uint64_t limit) {
    if (points.size() < 3) return 0;
    csg::Bounds2 box;
    for (const Vec2& p : points) box.add(p);
    const int side = std::clamp(int(std::sqrt(double(points.size()))), 1, 2048);
    const Vec2 size = box.hi - box.lo;
    const Vec2 cell(size.x > 0 ? size.x / side : 1.0, size.y > 0 ? size.y / side : 1.0);
    auto cellOf = [&](double v, double lo, double width) {
        return std::clamp(int((v - lo) / width), 0, side - 1);
    };
    std::vector<uint32_t> filed(size_t(side) * size_t(side), 0);
    uint64_t pairs = 0, work = 0;
    for (size_t i = 0; i + 1 < points.size(); ++i) {
        const Vec2 a = points[i], b = points[i + 1];
        const int x0 = cellOf(std::min(a.x, b.x), box.lo.x, cell.x);
        const int x1 = cellOf(std::max(a.x, b.x), box.lo.x, cell.x);
        const int y0 = cellOf(std::min(a.y, b.y), box.lo.y, cell.y);
        const int y1 = cellOf(std::max(a.y, b.y), box.lo.y, cell.y);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                uint32_t& count = filed[size_t(y) * size_t(side) + size_t(x)];
                pairs += count++;
                if (pairs > limit || ++work > limit) return limit + 1;
            }
    }
    return pairs;
}

// The sum over the polyline's edges of the scanlines (distinct vertex y) each spans: the
// length of Clipper's active edge lists summed over its sweep. Counting stops past `limit`.
uint64_t sweepWork(const std::vector<Vec2>& points, uint64_t limit) {
    std::vector<double> ys;
    ys.reserve(points.size());
    for (const Vec2& p : points) ys.push_back(p.y);
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    uint64_t work = 0;
    for (size_t i = 0; i + 1 < points.size(); ++i) {
        const auto [lo, hi] = std::minmax(points[i].y, points[i + 1].y);
        work += uint64_t(std::upper_bound(ys.begin(), ys.end(), hi) -
                         std::lower_bound(ys.begin(), ys.end(), lo));
        if (work > limit) return limit + 1;
    }
    return work;
}

// A polyline through the curve, its start excluded, with chords within kStrokeChordTolerance
// (the second derivative bounds a chord's distance from the curve: |f''| h^2 / 8), at most
// kMaxStrokeChords of them.
void flatten(const Segment2& s, std::vector<Vec2>& out) {
    double curvature = 0.0;  // a bound on |f''(u)|, u in [0, 1]
    switch (s.kind) {
        case Segment2::Kind::Line:
            out.push_back(s.p[1]);
            return;
        case Segment2::Kind::Quadratic:
            curvature = 2.0 * glm::length(s.p[0] - 2.0 * s.p[1] + s.p[2]);
            break;
        case Segment2::Kind::Cubic:
            curvature = 6.0 * std::max(glm::length(s.p[0] - 2.0 * s.p[1] + s.p[2]),
                                       glm::length(s.p[1] - 2.0 * s.p[2] + s.p[3]));
            break;
        case Segment2::Kind::Arc: {
            const double sweep = s.th1 - s.th0;
            curvature = sweep * sweep * (glm::length(s.p[2]) + glm::length(s.p[3]));
            break;
        }
    }
    const double chords = std::ceil(std::sqrt(curvature / (8.0 * kStrokeChordTolerance)));
    const uint64_t n = uint64_t(std::clamp(chords, 1.0, kMaxStrokeChords));
    for (uint64_t k = 1; k < n; ++k) out.push_back(s.at(double(k) / double(n)));
    out.push_back(s.finish());
}

// A path's subpaths, filled or stroked as libsvg's path::set_attrs decides (see the header's
// notation). Faceted, a subpath is libsvg's point list; exact, its segments.
class PathBuilder {
public:
    PathBuilder(ShapeSink& sink, const Stroke& stroke) : sink_(sink), stroke_(stroke) {}

    Vec2 current() const { return current_; }
    // Points and segments held for the subpath being read.
    uint64_t pending() const { return points_.size() + segments_.size(); }

    void moveTo(Vec2 p) {
        if (started_) endSubpath(isOpen());
        started_ = true;
        first_ = p;
        points_ = {p};
        current_ = p;
    }

    void lineTo(Vec2 p) {
        if (sink_.faceted())
            point(p);
        else
            segment(Segment2::line(current_, p));
        current_ = p;
    }

    // libsvg's curve_to: 20 chords at u = k / 20.
    void quadTo(Vec2 c, Vec2 p) {
        if (sink_.faceted()) {
            const Vec2 a = current_;
            for (int k = 1; k <= 20; ++k) {
                const double u = k * (1.0 / 20.0), v = 1.0 - u;
                point(a * (v * v) + c * (2.0 * v * u) + p * (u * u));
            }
        } else {
            segment(Segment2::quadratic(current_, c, p));
        }
        current_ = p;
    }

    void cubicTo(Vec2 c1, Vec2 c2, Vec2 p) {
        if (sink_.faceted()) {
            const Vec2 a = current_;
            for (int k = 1; k <= 20; ++k) {
                const double u = k * (1.0 / 20.0), v = 1.0 - u;
                point(a * (v * v * v) + c1 * (3.0 * v * v * u) + c2 * (3.0 * v * u * u) +
                      p * (u * u * u));
            }
        } else {
            segment(Segment2::cubic(current_, c1, c2, p));
        }
        current_ = p;
    }

    // SVG 1.1's arc (implementation notes F.6.5, as libsvg's arc_to computes it). A zero
    // radius makes a line and equal ends nothing, as SVG says (libsvg makes NaN points).
    void arcTo(double rx, double ry, double angle, bool large, bool sweep, Vec2 p) {
        const Vec2 a = current_;
        if (a == p) return;
        if (rx == 0.0 || ry == 0.0) return lineTo(p);
        const double cosA = openscadCosDegrees(angle), sinA = openscadSinDegrees(angle);
        const double dx = (a.x - p.x) / 2, dy = (a.y - p.y) / 2;
        const double x1 = cosA * dx + sinA * dy, y1 = -sinA * dx + cosA * dy;
        const double d = (x1 * x1) / (rx * rx) + (y1 * y1) / (ry * ry);
        if (d > 1) {
            rx = std::fabs(std::sqrt(d) * rx);
            ry = std::fabs(std::sqrt(d) * ry);
        }
        double t1 = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
        const double t2 = rx * rx * y1 * y1 + ry * ry * x1 * x1;
        if (t1 < 0) t1 = 0;
        double t3 = std::sqrt(t1 / t2);
        if (large == sweep) t3 = -t3;
        const double cx1 = t3 * rx * y1 / ry, cy1 = t3 * -ry * x1 / rx;
        const Vec2 center(cosA * cx1 - sinA * cy1 + (a.x + p.x) / 2.0,
                          sinA * cx1 + cosA * cy1 + (a.y + p.y) / 2.0);
        const double ux = (x1 - cx1) / rx, uy = (y1 - cy1) / ry;
        const double vx = (-x1 - cx1) / rx, vy = (-y1 - cy1) / ry;
        if (!std::isfinite(center.x) || !std::isfinite(center.y)) return lineTo(p);
        if (sink_.faceted()) {
            // libsvg's vector_angle, in degrees, and its chords (the start point again first).
            auto angleBetween = [](double ax, double ay, double bx, double by) {
                double r = openscadAtan2Degrees(by, bx) - openscadAtan2Degrees(ay, ax);
                return r < 0 ? r + 360 : r;
            };
            const double theta = angleBetween(1, 0, ux, uy);
            double delta = angleBetween(ux, uy, vx, vy);
            if (!sweep) delta -= 360;
            const int steps = int(std::fabs(delta) * 10.0 / 180 + 4);
            for (int k = 0; k <= steps; ++k) {
                const double phi = theta + delta * k / steps;
                const double c = openscadCosDegrees(phi), s = openscadSinDegrees(phi);
                point(Vec2(cosA * c * rx - sinA * s * ry + center.x,
                           sinA * c * rx + cosA * s * ry + center.y));
            }
        } else {
            const Vec2 axisA(cosA * rx, sinA * rx), axisB(-sinA * ry, cosA * ry);
            const double theta = std::atan2(uy, ux);
            double delta = std::atan2(vy, vx) - theta;
            if (delta < 0) delta += 2 * kPi;
            if (!sweep) delta -= 2 * kPi;
            // Never a whole turn: the ends differ.
            const double sweepAngle = std::min(std::fabs(delta), std::nextafter(2 * kPi, 0.0));
            if (sweepAngle == 0.0) return lineTo(p);
            Segment2 s = delta > 0
                             ? Segment2::arc(center, axisA, axisB, theta, theta + sweepAngle)
                             : Segment2::arc(center, axisA, -axisB, -theta, -theta + sweepAngle);
            s.p[0] = a;
            s.end = p;
            segment(s);
        }
        current_ = p;
    }

    // Z: the subpath ends where it began (libsvg adds its first point again) and is filled;
    // what follows without a moveto starts a new one. Faceted, as libsvg, its first point is
    // the next point made (the point Z returned to is left out); exact, as SVG says, it starts
    // at the point Z returned to.
    void close() {
        if (started_) {
            if (sink_.faceted()) {
                points_.push_back(points_.front());
                current_ = points_.front();
            } else {
                segment(Segment2::line(current_, first_));
                current_ = first_;
            }
            endSubpath(false);
        }
        started_ = false;
        closedSeen_ = true;
    }

    // The end of the data: libsvg strokes the last subpath only if the path has no Z at all.
    void finish() {
        if (started_) endSubpath(!closedSeen_ && isOpen());
        started_ = false;
    }

private:
    bool isOpen() const {
        const Vec2 last = sink_.faceted() ? points_.back() : current_;
        return glm::length(last - first_) > kOpenDistance;
    }

    void point(Vec2 p) {
        if (!started_) {
            started_ = true;
            first_ = p;
            points_.clear();
        }
        points_.push_back(p);
    }

    void segment(const Segment2& s) {
        if (!started_) {
            started_ = true;
            first_ = s.start();
            points_.clear();
        }
        segments_.push_back(s);
    }

    void endSubpath(bool stroked) {
        if (sink_.faceted()) {
            if (stroked)
                sink_.stroke(points_, stroke_);
            else
                sink_.polygon(points_);
        } else if (stroked) {
            std::vector<Vec2> polyline{first_};
            for (const Segment2& s : segments_) {
                flatten(s, polyline);
                // stroke() charges at least 4 segments a point: stop before the budget.
                if (polyline.size() > sink_.remaining() / 4) {
                    sink_.fail("a stroke would have more than " +
                               std::to_string(sink_.remaining()) + " segments");
                    break;
                }
            }
            sink_.stroke(polyline, stroke_);
        } else {
            for (const Segment2& s : segments_) sink_.add(s);
            if (current_ != first_) sink_.add(Segment2::line(current_, first_));
        }
        segments_.clear();
        points_.clear();
        started_ = false;
    }

    ShapeSink& sink_;
    Stroke stroke_;
    bool started_ = false;
    bool closedSeen_ = false;
    Vec2 first_{0.0}, current_{0.0};
    std::vector<Vec2> points_;        // faceted
    std::vector<Segment2> segments_;  // exact
};

// How many numbers each command takes.
int argumentCount(char command) {
    switch (command) {
        case 'M':
        case 'L':
        case 'T':
            return 2;
        case 'H':
        case 'V':
            return 1;
        case 'C':
            return 6;
        case 'S':
        case 'Q':
            return 4;
        case 'A':
            return 7;
        default:
            return 0;
    }
}

}  // namespace

bool ShapeSink::charge(uint64_t n) {
    if (error_) return false;
    if (n > max_ || total_ > max_ - n) {
        fail("the drawing has more than " + std::to_string(max_) + " segments");
        return false;
    }
    total_ += n;
    return true;
}

void ShapeSink::add(const Segment2& s) {
    if (s.kind == Segment2::Kind::Line && s.p[0] == s.p[1]) return;
    if (!charge(1)) return;
    segments_.push_back(s);
}

void ShapeSink::polygon(const std::vector<Vec2>& points) {
    if (points.size() < 2) return;
    for (size_t i = 0; i < points.size(); ++i)
        add(Segment2::line(points[i], points[(i + 1) % points.size()]));
}

void ShapeSink::stroke(const std::vector<Vec2>& polyline, const Stroke& stroke) {
    if (polyline.empty() || error_) return;
    const double delta = stroke.width * (kStrokeScale / 2.0);
    // What Clipper will make, charged before it runs: a few points a vertex, and round joins
    // and caps pi / acos(1 - tolerance / delta) points to a turn, for the turns the polyline
    // makes and the two caps' half turns each side.
    double estimate = 6.0 * double(polyline.size() + 2);
    if (stroke.join == StrokeJoin::Round || stroke.cap == StrokeCap::Round) {
        const double y = std::min(kClipperArcTolerance, delta * kClipperArcTolerance);
        const double perTurn = kPi / std::acos(1.0 - y / delta);
        double turning = 2 * kPi;
        Vec2 previous(0.0);
        for (size_t i = 0; i + 1 < polyline.size(); ++i) {
            const Vec2 d = polyline[i + 1] - polyline[i];
            if (d == Vec2(0.0)) continue;
            if (previous != Vec2(0.0))
                turning += std::abs(std::atan2(previous.x * d.y - previous.y * d.x,
                                               previous.x * d.x + previous.y * d.y));
            previous = d;
        }
        estimate += 2.0 * perTurn * turning / (2 * kPi);
    }
    if (!(estimate < double(max_))) {
        fail("a stroke would have more than " + std::to_string(max_) + " segments");
        return;
    }
    if (!charge(uint64_t(estimate))) return;
    if (crossingCandidates(polyline, kMaxCrossingCandidates) > kMaxCrossingCandidates) {
        fail("a stroked path doubles back on itself too often to stroke (more than " +
             std::to_string(kMaxCrossingCandidates) + " pairs of its " +
             std::to_string(polyline.size() - 1) + " edges may cross)");
        return;
    }
    if (sweepWork(polyline, kMaxSweepWork) > kMaxSweepWork) {
        fail("a stroked path winds round too often to stroke (its " +
             std::to_string(polyline.size() - 1) + " edges span more than " +
             std::to_string(kMaxSweepWork) + " scanlines in all)");
        return;
    }
    cl::Path line;
    line.reserve(polyline.size());
    for (const Vec2& p : polyline)  // truncated toward zero, as libsvg converts
        line.emplace_back(cl::cInt(p.x * kStrokeScale), cl::cInt(p.y * kStrokeScale));
    const cl::JoinType join = stroke.join == StrokeJoin::Round    ? cl::jtRound
                              : stroke.join == StrokeJoin::Square ? cl::jtSquare
                                                                  : cl::jtMiter;
    const cl::EndType end = stroke.cap == StrokeCap::Round  ? cl::etOpenRound
                            : stroke.cap == StrokeCap::Butt ? cl::etOpenButt
                                                            : cl::etOpenSquare;
    cl::Paths result;
    try {
        cl::ClipperOffset offset;
        offset.AddPath(line, join, end);
        offset.Execute(result, delta);
    } catch (...) {
        fail("a stroke's coordinates are beyond Clipper's range");
        return;
    }
    // The estimate was charged; the outline's own segments are what is kept.
    total_ -= uint64_t(estimate);
    for (const cl::Path& path : result) {
        std::vector<Vec2> points;
        points.reserve(path.size());
        for (const cl::IntPoint& q : path)
            points.emplace_back(double(q.X) / kStrokeScale, double(q.Y) / kStrokeScale);
        polygon(points);
    }
}

std::optional<double> wholeNumber(std::string_view text) {
    size_t pos = 0;
    std::string bad;
    const auto v = scanNumber(text, pos, &bad);
    if (!v || pos != text.size()) return std::nullopt;
    return v;
}

std::optional<std::string> numberList(std::string_view text, std::vector<double>& out) {
    size_t pos = 0;
    while (pos < text.size() && isWsp(text[pos])) ++pos;
    while (pos < text.size()) {
        std::string bad;
        const auto v = scanNumber(text, pos, &bad);
        if (!v) return bad.empty() ? "expected a number at column " + std::to_string(pos + 1) : bad;
        out.push_back(*v);
        skipSeparator(text, pos);
    }
    return std::nullopt;
}

std::optional<std::string> pathShape(std::string_view d, const Stroke& stroke, ShapeSink& sink) {
    PathBuilder path(sink, stroke);
    size_t pos = 0;
    char command = 0;  // upper case
    bool relative = false;
    // The previous command's last control point, for S and T.
    Vec2 lastCubic(0.0), lastQuad(0.0);
    char previous = 0;
    bool notedFlags = false;
    while (pos < d.size() && isWsp(d[pos])) ++pos;
    while (pos < d.size() && !sink.error()) {
        const char c = d[pos];
        const char upper = char(std::toupper(static_cast<unsigned char>(c)));
        if (std::isalpha(static_cast<unsigned char>(c))) {
            if (std::string_view("MLHVCSQTAZ").find(upper) == std::string_view::npos)
                return "unknown path command '" + std::string(1, c) + "' at column " +
                       std::to_string(pos + 1);
            if (command == 0 && upper != 'M')
                return "path data must begin with a moveto (M or m), not '" + std::string(1, c) +
                       "'";
            command = upper;
            relative = c != upper;
            ++pos;
            if (command == 'Z') {
                path.close();
                previous = 'Z';
                while (pos < d.size() && isWsp(d[pos])) ++pos;
                continue;
            }
        } else if (command == 0 || command == 'Z') {
            return "expected a path command at column " + std::to_string(pos + 1);
        }
        // One command's numbers (flags of A are single digits, separators optional).
        double v[7];
        const int count = argumentCount(command);
        while (pos < d.size() && isWsp(d[pos])) ++pos;
        for (int k = 0; k < count; ++k) {
            if (k > 0) skipSeparator(d, pos);
            if (command == 'A' && (k == 3 || k == 4)) {
                if (pos < d.size() && (d[pos] == '0' || d[pos] == '1')) {
                    v[k] = d[pos++] == '1';
                    // libsvg splits numbers at spaces, commas and signs only: "00" is one.
                    if (!notedFlags && pos < d.size() && !isWsp(d[pos]) && d[pos] != ',') {
                        notedFlags = true;
                        sink.note("arc flags written without a separator (column " +
                                  std::to_string(pos) +
                                  " of the path data) are read as SVG defines them; OpenSCAD "
                                  "2021 misreads them");
                    }
                    continue;
                }
                return "expected an arc flag (0 or 1) at column " + std::to_string(pos + 1);
            }
            std::string bad;
            const auto x = scanNumber(d, pos, &bad);
            if (!x && bad.empty() && pos >= d.size())
                return "the path data ends where a number of '" + std::string(1, command) +
                       "' is due";
            if (!x)
                return (bad.empty() ? "expected a number" : bad) + " at column " +
                       std::to_string(pos + 1) + " of the path data";
            v[k] = *x;
        }
        skipSeparator(d, pos);
        const Vec2 at = path.current();
        const Vec2 base = relative ? at : Vec2(0.0);
        switch (command) {
            case 'M':
                path.moveTo(base + Vec2(v[0], v[1]));
                command = 'L';  // further pairs are lines
                break;
            case 'L':
                path.lineTo(base + Vec2(v[0], v[1]));
                break;
            case 'H':
                path.lineTo(Vec2((relative ? at.x : 0.0) + v[0], at.y));
                break;
            case 'V':
                path.lineTo(Vec2(at.x, (relative ? at.y : 0.0) + v[0]));
                break;
            case 'C':
            case 'S': {
                const bool smooth = command == 'S';
                const Vec2 c1 = smooth ? (previous == 'C' ? 2.0 * at - lastCubic : at)
                                       : base + Vec2(v[0], v[1]);
                const int k = smooth ? 0 : 2;
                const Vec2 c2 = base + Vec2(v[k], v[k + 1]);
                path.cubicTo(c1, c2, base + Vec2(v[k + 2], v[k + 3]));
                lastCubic = c2;
                break;
            }
            case 'Q':
            case 'T': {
                const bool smooth = command == 'T';
                const Vec2 c1 =
                    smooth ? (previous == 'Q' ? 2.0 * at - lastQuad : at) : base + Vec2(v[0], v[1]);
                const int k = smooth ? 0 : 2;
                path.quadTo(c1, base + Vec2(v[k], v[k + 1]));
                lastQuad = c1;
                break;
            }
            case 'A':
                path.arcTo(std::fabs(v[0]), std::fabs(v[1]), v[2], v[3] != 0, v[4] != 0,
                           base + Vec2(v[5], v[6]));
                break;
            default:
                break;
        }
        if (path.pending() > sink.remaining())
            sink.fail("the drawing has more segments than the budget allows");
        // S and T reflect the control point of a C or S (Q or T) just before them.
        previous = command == 'S' ? 'C' : command == 'T' ? 'Q' : command;
    }
    if (sink.error()) return sink.error();
    path.finish();
    return sink.error();
}

void rectShape(double x, double y, double width, double height, double rx, double ry,
               const Stroke& stroke, ShapeSink& sink) {
    const bool hasRx = !(std::fabs(rx) < 1e-8), hasRy = !(std::fabs(ry) < 1e-8);
    if (!hasRx && !hasRy) {
        sink.polygon(
            {Vec2(x, y), Vec2(x + width, y), Vec2(x + width, y + height), Vec2(x, y + height)});
        return;
    }
    if (!hasRx) rx = ry;
    if (!hasRy) ry = rx;
    rx = std::min(rx, width / 2);
    ry = std::min(ry, height / 2);
    // libsvg's path: M H A V A H A V A z, every arc "rx,ry 0 0,1".
    PathBuilder path(sink, stroke);
    path.moveTo(Vec2(x + rx, y));
    path.lineTo(Vec2(x + width - rx, y));
    path.arcTo(std::fabs(rx), std::fabs(ry), 0, false, true, Vec2(x + width, y + ry));
    path.lineTo(Vec2(x + width, y + height - ry));
    path.arcTo(std::fabs(rx), std::fabs(ry), 0, false, true, Vec2(x + width - rx, y + height));
    path.lineTo(Vec2(x + rx, y + height));
    path.arcTo(std::fabs(rx), std::fabs(ry), 0, false, true, Vec2(x, y + height - ry));
    path.lineTo(Vec2(x, y + ry));
    path.arcTo(std::fabs(rx), std::fabs(ry), 0, false, true, Vec2(x + rx, y));
    path.close();
    path.finish();
}

void ellipseShape(double cx, double cy, double rx, double ry, ShapeSink& sink) {
    if (rx == 0.0 || ry == 0.0) return;
    if (sink.faceted()) {
        // libsvg's draw_ellipse: 40 points from 9 degrees on.
        std::vector<Vec2> points;
        for (int k = 1; k <= 40; ++k) {
            const double a = k * 360.0 / 40;
            points.emplace_back(rx * openscadSinDegrees(a) + cx, ry * openscadCosDegrees(a) + cy);
        }
        sink.polygon(points);
        return;
    }
    sink.add(Segment2::arc(Vec2(cx, cy), Vec2(0.0, ry), Vec2(rx, 0.0), 0.0, 2 * kPi));
}

}  // namespace io::detail
