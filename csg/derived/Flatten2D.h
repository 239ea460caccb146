// Curves of outlines (primitives/Outline.h) replaced by chords, for the operations that need
// lines or circles: an offset of an elliptic arc or a Bezier is neither, and Clipper and the
// hulls take points. Each chord's ends lie on the curve and no point of the curve is farther
// than `tolerance` from its chord.
#pragma once

#include <vector>

#include "primitives/Outline.h"

namespace csg {

// Whether s is an arc of a circle (its two axes orthogonal and of one length, to 1e-12).
bool isCircular(const Segment2& s);

// Whether every segment of the outline is a straight line (it needs no chords).
bool straightEdged(const Outline& outline);

// Appends s to out as it is when it is a line or a circular arc, else as chords (the first
// starts at s.start(), the last ends at s.finish(), the very doubles). Returns whether chords
// were made.
bool appendLinesAndCircles(const Segment2& s, double tolerance, std::vector<Segment2>& out);

// Appends the points of s's chords to out: s.start() and the inner points, not s.finish()
// (the next segment's start). Circular arcs too.
void appendChordPoints(const Segment2& s, double tolerance, std::vector<Vec2>& out);

// The number of equal angular steps that keep a circle of radius r within `tolerance` of its
// chords over `angle` radians: at least 1, at most 1e5.
int64_t chordSteps(double r, double angle, double tolerance);

}  // namespace csg
