// The boundary of a 2-D shape as the result of its booleans, not of its leaves: what offset()
// grows or shrinks and what hull() wraps. A 2-D shape is a tree of Extrusion::Plane leaves
// (io/Shapes2D.h) whose union, intersection and difference are the tree's own operators; the
// boundary of the result is made of pieces of the leaves' outlines.
//
// How: every outline segment is split where it meets another (of any leaf, its own included),
// so that no piece crosses another one; then the shape is asked on both sides of each piece's
// middle (Region2D::inside). A piece with the shape on exactly one side bounds it; it is turned
// so that the shape lies on its left. Coincident pieces (two squares sharing an edge, the
// same arc in two leaves) are split at each other's ends, so they are the very same pieces,
// and the side test agrees on them: one is kept, never half of one.
//
// Pieces are straight or circular. An elliptic arc (a circle under a non-uniform scale) or a
// Bezier (a glyph) has no circular offset, so the boundary replaces it by chords within
// tol::kFlattenRel of the shape's size and says so (Boundary2D::approximated).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "csg/Tree.h"

namespace csg {

// A straight segment or a circular arc of a boundary, directed with the shape on its left.
struct BoundaryPiece {
    enum class Kind : uint8_t { Line, Arc };
    Kind kind = Kind::Line;
    Vec2 a{0.0}, b{0.0};  // start and end; b == a for a whole circle
    // Arc: the circle, and the angle (radians) of a about the centre; the arc turns from there
    // by sweep, counter-clockwise where sweep > 0, at most a whole turn.
    Vec2 center{0.0};
    double radius = 0.0;
    double angle0 = 0.0;
    double sweep = 0.0;

    // The point at u in [0, 1] (u = 0 is a, u = 1 is b up to rounding).
    Vec2 at(double u) const;
    // The unit tangent at u, in the piece's direction.
    Vec2 direction(double u) const;
    double length() const;
    // The same piece run backwards (the shape then lies on its right).
    BoundaryPiece reversed() const;
    // The tightest box: its ends and, for an arc, where it meets the axes through its centre.
    Bounds2 bounds() const;
};

// The piece of a line or circular arc segment (isCircular in csg/derived/Flatten2D.h), in the
// segment's direction.
BoundaryPiece boundaryPieceOf(const Segment2& s);
// The segment of a piece, in its direction, starting and ending on the piece's very doubles.
Segment2 segmentOf(const BoundaryPiece& p);

// The shape's boundary, in no particular order: each piece's ends are the very doubles of its
// neighbours' ends, so the pieces chain into closed curves.
struct Boundary2D {
    std::vector<BoundaryPiece> pieces;
    // True when elliptic arcs or Beziers were replaced by chords (within tol::kFlattenRel).
    bool approximated = false;
};

// The points of a 2-D shape: a copy of its tree with every outline made of lines and circular
// arcs only (see above), and the test of a point against it. A point on a boundary may go
// either way.
class Region2D {
public:
    explicit Region2D(const Node& shape);
    bool inside(Vec2 p) const;
    // Every segment of every leaf, once (all Line or circular Arc).
    const std::vector<Outline>& outlines() const { return outlines_; }
    // max(1, largest |coordinate| of the outlines): the scale of the relative tolerances.
    double size() const { return size_; }
    bool approximated() const { return approximated_; }

private:
    struct Item {
        Op op = Op::Leaf;
        int32_t left = -1, right = -1;  // operators
        int32_t outline = -1;           // leaves
    };
    int32_t add(const Node& node, const glm::dmat2& m, Vec2 shift);
    bool inside(int32_t item, Vec2 p) const;

    // A leaf's segments sorted into horizontal strips: the point test counts the crossings of
    // a horizontal line, which only segments whose y range contains the point's can make.
    // Within a strip the segments still share their ends, so the parity stays watertight.
    struct Strips {
        double y0 = 0.0, height = 1.0;
        std::vector<Outline> strips;
    };
    void buildStrips(size_t leaf);

    std::vector<Outline> outlines_;
    std::vector<Bounds2> boxes_;
    std::vector<Strips> strips_;
    std::vector<Item> items_;
    int32_t root_ = -1;
    double size_ = 1.0;
    bool approximated_ = false;
};

// The boundary of the shape (see the top of this file). Never throws; a shape with no area
// has no boundary.
Boundary2D boundaryOf(const Region2D& region);

// Where pieces meet at a vertex, the outgoing piece (an index into outs) that bounds the same
// corner of the shape as an incoming piece arriving in direction `in`: the first met turning
// clockwise from -in. Two shapes touching at a vertex keep their corners apart this way.
size_t cornerPartner(const std::vector<BoundaryPiece>& pieces, Vec2 in,
                     const std::vector<size_t>& outs);

// A closed curve of the boundary: each piece starts where the one before it ends, and the
// last ends where the first starts (a whole circle is a contour of one piece).
using Contour2D = std::vector<BoundaryPiece>;

// The boundary chained into closed contours, the shape on their left (outer contours turn
// counter-clockwise, holes clockwise), each vertex joining the pieces cornerPartner() pairs.
// Neighbouring pieces of one line (the vertex between them within tol::kBoundaryPointRel of
// the shape's size of it) or of one circle are merged again: the splitting cut them, the
// drawing does not need the cut. nullopt when a piece's end has no continuation, which the
// splitting rules out (its ends are the very doubles of its neighbours').
std::optional<std::vector<Contour2D>> contoursOf(const Boundary2D& boundary);

}  // namespace csg
