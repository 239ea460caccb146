#include "csg/derived/Flatten2D.h"

#include <algorithm>
#include <cmath>

namespace csg {

namespace {

// Most chords one curve becomes: a bound on work and memory for absurd tolerances.
constexpr int64_t kMaxChords = 100000;

// The number of uniform parameter steps that keep a Bezier within tolerance of its chords:
// the chord error of a step h is at most max |B''| h^2 / 8.
int64_t bezierSteps(const Segment2& s, double tolerance) {
    double second = 0.0;
    if (s.kind == Segment2::Kind::Quadratic) {
        second = 2.0 * glm::length(s.p[0] - 2.0 * s.p[1] + s.p[2]);
    } else {
        second = 6.0 * std::max(glm::length(s.p[0] - 2.0 * s.p[1] + s.p[2]),
                                glm::length(s.p[1] - 2.0 * s.p[2] + s.p[3]));
    }
    const double steps = std::ceil(std::sqrt(second / (8.0 * tolerance)));
    return std::clamp<int64_t>(std::isfinite(steps) ? int64_t(std::min(steps, 1e9)) : 1, 1,
                               kMaxChords);
}

int64_t stepsOf(const Segment2& s, double tolerance) {
    switch (s.kind) {
        case Segment2::Kind::Line:
            return 1;
        case Segment2::Kind::Quadratic:
        case Segment2::Kind::Cubic:
            return bezierSteps(s, tolerance);
        case Segment2::Kind::Arc: {
            // An ellipse is within its larger axis's circle's chord error.
            const double r = std::max(glm::length(s.p[2]), glm::length(s.p[3]));
            return chordSteps(r, s.th1 - s.th0, tolerance);
        }
    }
    return 1;
}

}  // namespace

int64_t chordSteps(double r, double angle, double tolerance) {
    if (!(r > tolerance) || !(angle > 0.0)) return 1;
    // The sagitta of a step phi is r (1 - cos(phi / 2)).
    const double step = 2.0 * std::acos(1.0 - tolerance / r);
    const double steps = std::ceil(angle / step);
    return std::clamp<int64_t>(std::isfinite(steps) ? int64_t(std::min(steps, 1e9)) : 1, 1,
                               kMaxChords);
}

bool isCircular(const Segment2& s) {
    if (s.kind != Segment2::Kind::Arc) return false;
    const double la = glm::length(s.p[2]), lb = glm::length(s.p[3]);
    return std::abs(la - lb) <= 1e-12 * std::max(la, lb) &&
           std::abs(glm::dot(s.p[2], s.p[3])) <= 1e-12 * la * lb;
}

void appendChordPoints(const Segment2& s, double tolerance, std::vector<Vec2>& out) {
    const int64_t n = stepsOf(s, tolerance);
    out.push_back(s.start());
    for (int64_t k = 1; k < n; ++k) out.push_back(s.at(double(k) / double(n)));
}

bool straightEdged(const Outline& outline) {
    return std::all_of(outline.segments.begin(), outline.segments.end(),
                       [](const Segment2& s) { return s.kind == Segment2::Kind::Line; });
}

bool appendLinesAndCircles(const Segment2& s, double tolerance, std::vector<Segment2>& out) {
    if (s.kind == Segment2::Kind::Line || isCircular(s)) {
        out.push_back(s);
        return false;
    }
    std::vector<Vec2> points;
    appendChordPoints(s, tolerance, points);
    points.push_back(s.finish());
    for (size_t k = 0; k + 1 < points.size(); ++k)
        out.push_back(Segment2::line(points[k], points[k + 1]));
    return true;
}

}  // namespace csg
