// Notation: phi is a direction (radians); a site's support value at phi is h(phi) = c . u(phi)
// + rho (a point: its c with rho = 0), defined for phi in its window [from, from + width]
// (a point's window is the whole turn). The trace is a list of visits: the site that is the
// maximum from one event angle to the next.
#include "csg/derived/Hull2D.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "csg/derived/Flatten2D.h"

namespace csg {

namespace {

constexpr double kTurn = 2.0 * kPi;
// Angles closer than this are one (radians): far below any tangent's rounding error for
// radii above 1e-6 of the hull's size, far above double's resolution of angles.
constexpr double kAngleSlack = 1e-11;

double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}

Vec2 unitAt(double angle) {
    return {std::cos(angle), std::sin(angle)};
}

double wrap(double angle) {
    angle = std::fmod(angle, kTurn);
    return angle < 0.0 ? angle + kTurn : angle;
}

struct Site {
    Vec2 c{0.0};
    double rho = 0.0;
    double from = 0.0, width = kTurn;  // the window

    bool active(double phi) const {
        if (width >= kTurn) return true;
        const double off = wrap(phi - from);
        return off <= width + kAngleSlack || off >= kTurn - kAngleSlack;
    }
    double value(double phi) const { return glm::dot(c, unitAt(phi)) + rho; }
    Vec2 support(double phi) const { return c + unitAt(phi) * rho; }
    // The angle, after `phi`, where the window closes; infinity for a whole turn.
    double closesAfter(double phi) const {
        if (width >= kTurn) return kInfinity;
        double off = wrap(from + width - phi);
        return off <= kAngleSlack ? off + kTurn : off;
    }
};

// Andrew's monotone chain: the strictly convex hull of the points, counter-clockwise.
std::vector<Vec2> pointHull(std::vector<Vec2> p) {
    std::sort(p.begin(), p.end(),
              [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    std::vector<Vec2> h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0.0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0.0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

// Whether the circle lies within the convex polygon (counter-clockwise): then its arcs never
// reach the hull.
bool circleInside(const std::vector<Vec2>& hull, Vec2 c, double rho) {
    if (hull.size() < 3) return false;
    for (size_t i = 0; i < hull.size(); ++i) {
        const Vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
        const Vec2 e = b - a;
        if (cross(e, c - a) / glm::length(e) < rho) return false;
    }
    return true;
}

// The first angle after phi (turned by at most a whole turn, more than kAngleSlack) where t
// overtakes s, or infinity. D(psi) = h_t - h_s = R cos(psi - theta) + C rises through 0 at
// psi = theta - acos(-C / R).
// A site that only touches s (a point on s's circle: D's maximum R + C is 0 up to rounding)
// never overtakes it.
double overtakes(const Site& s, const Site& t, double phi, double touch) {
    const Vec2 ab = t.c - s.c;
    const double radius = glm::length(ab), offset = t.rho - s.rho;
    if (!(radius > 0.0) || radius + offset <= touch || offset > radius * (1.0 + 1e-12))
        return kInfinity;
    const double theta = std::atan2(ab.y, ab.x);
    const double psi = theta - std::acos(std::clamp(-offset / radius, -1.0, 1.0));
    double turn = wrap(psi - phi);
    if (turn <= kAngleSlack) turn += kTurn;
    if (!t.active(phi + turn) || !s.active(phi + turn)) return kInfinity;
    return turn;
}

struct Visit {
    size_t site;
    double enter;  // the angle where it became the maximum (unwrapped)
};

}  // namespace

void addHullSites(const Node& shape, HullSites& sites) {
    const Region2D region(shape);
    sites.approximated |= region.approximated();
    bool unionOnly = true;
    std::function<void(const Node&)> scan = [&](const Node& n) {
        if (n.op == Op::Leaf) return;
        if (n.op != Op::Union) unionOnly = false;
        if (n.left) scan(*n.left);
        if (n.right) scan(*n.right);
    };
    scan(shape);
    auto add = [&](const BoundaryPiece& p) {
        sites.points.push_back(p.a);
        sites.points.push_back(p.b);
        if (p.kind == BoundaryPiece::Kind::Arc) sites.arcs.push_back(p);
    };
    if (unionOnly) {
        for (const Outline& o : region.outlines())
            for (const Segment2& s : o.segments) add(boundaryPieceOf(s));
        return;
    }
    for (const BoundaryPiece& p : boundaryOf(region).pieces) add(p);
}

Outline convexHull2D(const HullSites& input) {
    Outline out;
    const std::vector<Vec2> corners = pointHull(input.points);
    std::vector<Site> sites;
    for (const Vec2& p : corners) sites.push_back({p, 0.0, 0.0, kTurn});
    for (const BoundaryPiece& a : input.arcs) {
        if (!(a.radius > 0.0) || circleInside(corners, a.center, a.radius)) continue;
        const double width = std::min(std::abs(a.sweep), kTurn);
        const double from = a.sweep > 0.0 ? a.angle0 : a.angle0 + a.sweep;
        sites.push_back({a.center, a.radius, wrap(from), width});
    }
    const size_t pointSites = corners.size();
    if (sites.size() == pointSites) {
        if (corners.size() >= 3)
            for (size_t i = 0; i < corners.size(); ++i)
                out.segments.push_back(
                    Segment2::line(corners[i], corners[(i + 1) % corners.size()]));
        return out;
    }

    // The maximum at phi among the active sites; ties go to the one that leads just after.
    auto best = [&](double phi, size_t skip) {
        size_t found = sites.size();
        double top = -kInfinity, after = -kInfinity;
        for (size_t k = 0; k < sites.size(); ++k) {
            if (k == skip || !sites[k].active(phi)) continue;
            const double v = sites[k].value(phi), w = sites[k].value(phi + 1e-7);
            const double slack = 1e-12 * (std::abs(v) + std::abs(top));
            if (v > top + slack || (v >= top - slack && w > after)) found = k, top = v, after = w;
        }
        return found;
    };

    double size = 1.0;
    for (const Site& site : sites)
        size = std::max({size, std::abs(site.c.x), std::abs(site.c.y), site.rho});
    const double touch = 1e-12 * size;
    const double start = 0.123456789;  // any direction; one unlikely to be an event
    std::vector<Visit> visits{{best(start, sites.size()), start}};
    double turned = 0.0;
    for (size_t guard = 0; guard < 4 * sites.size() + 8; ++guard) {
        const size_t s = visits.back().site;
        const double phi = start + turned;
        double next = sites[s].closesAfter(phi);
        size_t to = sites.size();
        for (size_t t = 0; t < sites.size(); ++t) {
            if (t == s) continue;
            const double turn = overtakes(sites[s], sites[t], phi, touch);
            if (turn < next - kAngleSlack) {
                next = turn, to = t;
            } else if (turn <= next + kAngleSlack && to < sites.size()) {
                // Two sites at once (points on one line): the one that leads just after.
                const double psi = phi + turn + 1e-7;
                if (sites[t].value(psi) > sites[to].value(psi)) to = t;
            }
        }
        if (!(next < kInfinity) || turned + next >= kTurn - kAngleSlack) break;
        turned += next;
        if (to == sites.size()) to = best(start + turned + 1e-9, s);  // s's window closed
        if (to == sites.size()) break;
        visits.push_back({to, start + turned});
    }
    // Round the turn: the last visit carries on into the first when they are one site.
    if (visits.size() > 1 && visits.back().site == visits.front().site) {
        visits.front().enter = visits.back().enter - kTurn;
        visits.pop_back();
    }
    const size_t n = visits.size();
    std::vector<Vec2> enterPoint(n), leavePoint(n);
    std::vector<Segment2> arcs(n);
    for (size_t k = 0; k < n; ++k) {
        const Site& site = sites[visits[k].site];
        double leave = k + 1 < n ? visits[k + 1].enter : visits[0].enter + kTurn;
        if (n == 1) leave = visits[0].enter + kTurn;
        if (site.rho > 0.0 && leave > visits[k].enter) {
            arcs[k] = Segment2::arc(site.c, {site.rho, 0.0}, {0.0, site.rho}, visits[k].enter,
                                    std::min(leave, visits[k].enter + kTurn));
            enterPoint[k] = arcs[k].start();
            leavePoint[k] = arcs[k].finish();
        } else {
            enterPoint[k] = leavePoint[k] = site.c;
            arcs[k].kind = Segment2::Kind::Line;  // no arc
            arcs[k].p[0] = arcs[k].p[1] = site.c;
        }
    }
    for (size_t k = 0; k < n; ++k) {
        if (arcs[k].kind == Segment2::Kind::Arc) out.segments.push_back(arcs[k]);
        const Vec2 to = enterPoint[(k + 1) % n];
        if (leavePoint[k] != to) out.segments.push_back(Segment2::line(leavePoint[k], to));
    }
    // A hull without area (all points on one line, no circle) is nothing.
    double area = 0.0;
    for (const Segment2& s : out.segments) area += cross(s.start(), s.finish());
    bool anyArc = false;
    for (const Segment2& s : out.segments) anyArc |= s.kind == Segment2::Kind::Arc;
    if (!anyArc && !(std::abs(area) > 0.0)) out.segments.clear();
    return out;
}

}  // namespace csg
