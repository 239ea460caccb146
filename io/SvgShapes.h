// The geometry of one SVG element as OpenSCAD 2021's libsvg makes it (src/libsvg/path.cc,
// rect.cc, circle.cc, ellipse.cc, line.cc, polyline.cc, polygon.cc, shape.cc), in the
// element's own user units, before any transform. io/SvgFile.h reads the file around it.
//
// Notation: a *subpath* runs from a moveto to the next moveto or closepath. It is *closed* when
// it ends in Z or its last point lies within 0.1 of its first (libsvg's is_open_path); a closed
// subpath is filled (a straight line joins its ends), an open one is *stroked*: its polyline
// offset by half the stroke width with Clipper, as libsvg's offset_path. Exact segments keep
// curves as they are; faceted ones are OpenSCAD's chords: Beziers 20, arcs
// floor(|sweep degrees| / 18 + 4), circles and ellipses 40. Where two segments meet their ends
// are the very same doubles.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "primitives/Outline.h"

namespace io::detail {

// libsvg's reading of stroke-linejoin and stroke-linecap into Clipper's join and end types:
// join bevel -> square, round -> round, anything else -> miter (limit 2); cap butt, round,
// anything else -> square.
enum class StrokeJoin : uint8_t { Miter, Square, Round };
enum class StrokeCap : uint8_t { Butt, Square, Round };

struct Stroke {
    double width = 1.0;  // user units; libsvg takes anything below 0.01 as 1
    StrokeJoin join = StrokeJoin::Miter;
    StrokeCap cap = StrokeCap::Square;
};

// Where one element's segments go: the element's segments, in its user units, and the count
// of every segment made for the drawing so far, which may not pass maxSegments.
class ShapeSink {
public:
    ShapeSink(bool faceted, uint64_t maxSegments) : faceted_(faceted), max_(maxSegments) {}

    bool faceted() const { return faceted_; }
    // A segment of the current element (a straight one of no length is dropped).
    void add(const csg::Segment2& s);
    // The closed polygon through points (its last point joined to its first).
    void polygon(const std::vector<csg::Vec2>& points);
    // The outline of the polyline stroked as libsvg strokes it.
    void stroke(const std::vector<csg::Vec2>& polyline, const Stroke& stroke);
    // The error that stopped the element (too many segments), if any.
    const std::optional<std::string>& error() const { return error_; }
    void fail(std::string message) {
        if (!error_) error_ = std::move(message);
    }
    // A remark on how the element was read (for a warning at its line).
    void note(std::string message) { notes_.push_back(std::move(message)); }
    std::vector<std::string> takeNotes() { return std::move(notes_); }
    // Takes the current element's segments, leaving none.
    std::vector<csg::Segment2> take() { return std::move(segments_); }
    uint64_t total() const { return total_; }
    // Segments that may still be made.
    uint64_t remaining() const { return error_ ? 0 : max_ - total_; }

private:
    bool charge(uint64_t n);

    bool faceted_;
    uint64_t max_;
    uint64_t total_ = 0;
    std::vector<csg::Segment2> segments_;
    std::vector<std::string> notes_;
    std::optional<std::string> error_;
};

// The numbers of an SVG list (points="...", viewBox): separated by whitespace and/or one
// comma, each of SVG's number syntax, finite and at most 2^40 in magnitude. An error message
// when the text is not such a list.
std::optional<std::string> numberList(std::string_view text, std::vector<double>& out);

// One number as the whole text (SVG's number syntax), or nullopt.
std::optional<double> wholeNumber(std::string_view text);

// <path d="...">: the path data (SVG 1.1's grammar: M m L l H h V v C c S s Q q T t A a Z z,
// implicit repeats, flags without separators, which OpenSCAD 2021 misreads: noted), its
// subpaths filled or stroked as libsvg does.
// An error message (with the column in d) for data that does not follow the grammar or has a
// number that is not finite or above 2^40.
std::optional<std::string> pathShape(std::string_view d, const Stroke& stroke, ShapeSink& sink);

// <rect>: the rectangle, or with rx/ry > 0 (clamped to half the size; one given stands for
// both) the rounded rectangle libsvg writes as path data (its corners are arcs).
void rectShape(double x, double y, double width, double height, double rx, double ry,
               const Stroke& stroke, ShapeSink& sink);

// <circle> and <ellipse>: the ellipse (cx + rx sin a, cy + ry cos a), filled.
void ellipseShape(double cx, double cy, double rx, double ry, ShapeSink& sink);

}  // namespace io::detail
