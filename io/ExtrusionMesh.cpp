#include "io/ExtrusionMesh.h"

#include <clipper.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "csg/derived/Flatten2D.h"
#include "csg/mesh/EarClip.h"
#include "io/Degrees.h"
#include "primitives/base/Tolerances.h"

namespace io {

namespace {

using csg::Vec2;
using csg::Vec3;

// Clipper's integers hold the chords' corners on a grid of 2^-kGridBits of the outline's size (a
// power of two, so the way there and back is exact but for the rounding to an integer). Why 50:
// a corner moves by at most 2^-51 of the size, about an ulp, so a prism whose outline was turned
// in 2-D (a slot cut by rotate(120) square(...)) meets a solid turned in 3-D onto the same plane
// (the tab that fills the slot) to rounding; at 28 bits a corner moved by up to 1.9e-9 of the
// size, which tilted a 6-unit face by 4e-8 and set its plane 3.5e-7 off 12 units away, more than
// the exact boundary's weld, and Debian's example017 fell back to the grid. Clipper takes up to
// 62 bits (it switches to 128-bit products past 30 by itself).
// Every contour Clipper returns is cleaned of corners within kCleanDistance (1.415 steps of the
// grid of 2^-kCleanBits of the size: 3.4e-7 to 6.7e-7 of it) of their neighbours or of the line
// through them (Clipper's CleanPolygon, as OpenSCAD cleans its polygons). Why 22: a projection() of
// an STL (Debian's projection.scad) leaves fans of corners 1e-7 to 3e-7 apart at size 16, whose
// side faces are too small to cut and weld (the exact boundary welds at 1e-9 of the size) and
// sent the part to the grid; at 3.4e-7 of the size they merge, and the outline moves by less
// than that, far below any tolerance an export asks. The sign's glyphs and every other Debian
// example keep their corners (the same triangle counts as at 28 bits).
constexpr int kGridBits = 50;
constexpr int kCleanBits = 22;
constexpr double kCleanDistance = 1.415 * double(int64_t(1) << (kGridBits - kCleanBits));

using Polygon = RegionPolygon;

// chordRegion's work: false where it gives nullopt.
bool regionOf(const csg::Outline& outline, const csg::Bounds2& box, double chordDeviation,
              std::vector<Polygon>& region) {
    const double size = std::max({std::abs(box.lo.x), std::abs(box.lo.y), std::abs(box.hi.x),
                                  std::abs(box.hi.y), std::numeric_limits<double>::min()});
    const int sizeExponent = std::ilogb(size) + 1;  // size < 2^sizeExponent
    const double toGrid = std::ldexp(1.0, kGridBits - sizeExponent);
    const double unit = std::ldexp(1.0, sizeExponent - kGridBits);

    // The segments chained into closed walks at their shared ends (an outline's neighbouring
    // segments share the very same doubles; its segments may come in any order), one Clipper
    // path each. Where walks touch, which segment comes next does not matter: every
    // decomposition of the directed segments into closed walks has the same winding numbers.
    // Under the even-odd rule a segment may also be walked backwards: its direction does not
    // change the parity, and a drawing's paths (DXF) run their edges either way. A walk that
    // does not close (a dangling end) declines.
    const std::vector<csg::Segment2>& segments = outline.segments;
    const bool eitherWay = outline.rule == csg::FillRule::EvenOdd;
    const auto before = [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
    // Segment k's ends, k < n its start, k >= n its finish (walked backwards from there).
    const size_t n = segments.size();
    const auto endOf = [&](size_t k) {
        return k < n ? segments[k].start() : segments[k - n].finish();
    };
    std::vector<uint32_t> byEnd(eitherWay ? 2 * n : n);
    for (uint32_t i = 0; i < byEnd.size(); ++i) byEnd[i] = i;
    std::sort(byEnd.begin(), byEnd.end(),
              [&](uint32_t a, uint32_t b) { return before(endOf(a), endOf(b)); });
    std::vector<bool> used(n, false);
    // An unused segment that a walk at p can go on with: k (forwards) or n + k (backwards).
    const auto nextFrom = [&](Vec2 p) -> int64_t {
        auto it = std::lower_bound(byEnd.begin(), byEnd.end(), p,
                                   [&](uint32_t k, Vec2 q) { return before(endOf(k), q); });
        for (; it != byEnd.end() && endOf(*it) == p; ++it)
            if (!used[*it % n]) return *it;
        return -1;
    };
    ClipperLib::Paths paths;
    std::vector<Vec2> points;
    size_t corners = 0;
    for (uint32_t first = 0; first < n; ++first) {
        if (used[first]) continue;
        ClipperLib::Path& path = paths.emplace_back();
        const Vec2 start = segments[first].start();
        bool closed = false;
        for (int64_t step = first; step >= 0 && !closed;) {
            const csg::Segment2& segment = segments[size_t(step) % n];
            const bool backwards = size_t(step) >= n;
            used[size_t(step) % n] = true;
            points.clear();
            csg::appendChordPoints(segment, chordDeviation, points);
            if (backwards) {
                // The same chords from the finish: its points reversed, without the start.
                points.push_back(segment.finish());
                std::reverse(points.begin(), points.end());
                points.pop_back();
            }
            corners += points.size();
            if (corners > kMaxExtrusionMeshCorners) return false;
            for (const Vec2& p : points)
                path.push_back({ClipperLib::cInt(std::llround(p.x * toGrid)),
                                ClipperLib::cInt(std::llround(p.y * toGrid))});
            const Vec2 at = backwards ? segment.start() : segment.finish();
            closed = at == start;
            step = closed ? -1 : nextFrom(at);
        }
        if (!closed) return false;
    }

    // The region by the outline's fill rule, as outer contours with their holes.
    ClipperLib::Clipper clipper;
    clipper.StrictlySimple(true);
    ClipperLib::PolyTree tree;
    try {
        clipper.AddPaths(paths, ClipperLib::ptSubject, true);
        const ClipperLib::PolyFillType fill = outline.rule == csg::FillRule::EvenOdd
                                                  ? ClipperLib::pftEvenOdd
                                                  : ClipperLib::pftNonZero;
        if (!clipper.Execute(ClipperLib::ctUnion, tree, fill, fill)) return false;
    } catch (const ClipperLib::clipperException&) {
        return false;
    }

    const auto contourOf = [&](const ClipperLib::Path& path, std::vector<Vec2>& out) {
        ClipperLib::Path clean;
        ClipperLib::CleanPolygon(path, clean, kCleanDistance);
        for (const ClipperLib::IntPoint& q : clean)
            out.emplace_back(double(q.X) * unit, double(q.Y) * unit);
        return out.size() >= 3;
    };
    std::vector<const ClipperLib::PolyNode*> pending(tree.Childs.begin(), tree.Childs.end());
    while (!pending.empty()) {
        const ClipperLib::PolyNode* outer = pending.back();
        pending.pop_back();
        // An island inside a hole is an outer of its own.
        for (const ClipperLib::PolyNode* hole : outer->Childs)
            pending.insert(pending.end(), hole->Childs.begin(), hole->Childs.end());
        Polygon polygon;
        // Nothing left of it after cleaning: its holes are smaller still.
        if (!contourOf(outer->Contour, polygon.outer)) continue;
        for (const ClipperLib::PolyNode* hole : outer->Childs)
            if (!contourOf(hole->Contour, polygon.holes.emplace_back())) polygon.holes.pop_back();
        region.push_back(std::move(polygon));
    }
    return !region.empty();
}

// A polygon's corners in one list (the outer, then each hole), its loops as indices into it,
// and the triangles that fill it, counter-clockwise; false when ear clipping cannot cut it.
struct Cap {
    std::vector<Vec2> corners;
    std::vector<std::vector<uint32_t>> loops;
    std::vector<std::array<uint32_t, 3>> triangles;

    // straight: the ear clipper's minHeight (corners that close to the line through their
    // neighbours stay corners, see csg/mesh/EarClip.h).
    bool fill(const Polygon& polygon, double straight = 0.0) {
        const auto add = [&](const std::vector<Vec2>& contour) {
            std::vector<uint32_t>& loop = loops.emplace_back();
            for (const Vec2& p : contour) {
                loop.push_back(uint32_t(corners.size()));
                corners.push_back(p);
            }
        };
        add(polygon.outer);
        for (const std::vector<Vec2>& hole : polygon.holes) add(hole);
        const std::vector<std::vector<uint32_t>> holes(loops.begin() + 1, loops.end());
        return csg::earClip(corners, loops[0], holes, straight, triangles);
    }
};

// The mesh when it is closed (every edge used by an even number of faces) and, when asked, a
// manifold; nullopt otherwise.
std::optional<csg::Polyhedron> closedMesh(std::vector<Vec3> points, const csg::PolygonFaces& faces,
                                          bool manifold = true) {
    if (faces.size() == 0) return std::nullopt;
    csg::Polyhedron mesh = csg::Polyhedron::make(std::move(points), faces);
    if (mesh.invalidReason() || !mesh.edges().closed()) return std::nullopt;
    if (manifold && !mesh.edges().manifold()) return std::nullopt;
    return mesh;
}

// The prism (or frustum) over the region: the caps at z0 and z1, and a side quad per contour
// edge. Clipper winds outers counter-clockwise and holes clockwise, so the region is on the
// left of every edge and a quad from edge a -> b up faces out of it.
std::optional<csg::Polyhedron> prismOf(const std::vector<Polygon>& region, double z0, double z1,
                                       double scale) {
    std::vector<Vec3> points;
    csg::PolygonFaces faces;
    for (const Polygon& polygon : region) {
        Cap cap;
        if (!cap.fill(polygon)) return std::nullopt;
        // Corner k of the cap is point base + 2k at the bottom and base + 2k + 1 at the top.
        const uint32_t base = uint32_t(points.size());
        for (const Vec2& p : cap.corners) {
            points.emplace_back(p, z0);
            points.emplace_back(scale * p, z1);
        }
        const auto bottom = [&](uint32_t k) { return base + 2 * k; };
        for (const auto& t : cap.triangles) {
            faces.add({bottom(t[0]), bottom(t[2]), bottom(t[1])});              // facing down
            faces.add({bottom(t[0]) + 1, bottom(t[1]) + 1, bottom(t[2]) + 1});  // facing up
        }
        for (const std::vector<uint32_t>& loop : cap.loops)
            for (size_t k = 0, m = loop.size(); k < m; ++k) {
                const uint32_t a = bottom(loop[k]), b = bottom(loop[(k + 1) % m]);
                faces.add({a, b, b + 1, a + 1});
            }
    }
    return closedMesh(std::move(points), faces);
}

// The region (in the r, z half-plane) revolved about z through the meridians `turn` (the
// cosine and sine of each one's azimuth, turning counter-clockwise; `whole`: a full turn, the
// last meridian followed by the first): each contour edge sweeps a band of quads, isosceles
// trapezoids, so planar (a corner on the axis makes them triangles: Polyhedron::make welds its
// copies); a wedge has the region as its two end faces. With the region on the left of every
// edge (going up at r > 0 means the region is nearer the axis), the quad P_k, P_k+1, Q_k+1, Q_k
// of the edge P -> Q faces away from it; the start face, the region counter-clockwise in (r, z)
// laid on the first meridian's half-plane, faces back, out of a wedge that turns onwards.
std::optional<csg::Polyhedron> revolutionOf(const std::vector<Polygon>& region,
                                            const std::vector<Vec2>& turn, bool whole) {
    const int64_t meridians = int64_t(turn.size());
    const int64_t steps = whole ? meridians : meridians - 1;
    std::vector<Vec3> points;
    csg::PolygonFaces faces;
    for (const Polygon& polygon : region) {
        Cap cap;
        if (!cap.fill(polygon)) return std::nullopt;
        if (points.size() + cap.corners.size() * size_t(meridians) > kMaxRevolutionPoints)
            return std::nullopt;
        // Corner c of the cap on meridian k is point base + c * meridians + k.
        const uint32_t base = uint32_t(points.size());
        for (const Vec2& p : cap.corners)
            for (const Vec2& t : turn) points.emplace_back(p.x * t.x, p.x * t.y, p.y);
        const auto at = [&](uint32_t c, int64_t k) {
            return base + c * uint32_t(meridians) + uint32_t(k % meridians);
        };
        for (const std::vector<uint32_t>& loop : cap.loops)
            for (size_t i = 0, m = loop.size(); i < m; ++i) {
                const uint32_t p = loop[i], q = loop[(i + 1) % m];
                if (cap.corners[p].x == 0.0 && cap.corners[q].x == 0.0) continue;  // on the axis
                for (int64_t k = 0; k < steps; ++k)
                    faces.add({at(p, k), at(p, k + 1), at(q, k + 1), at(q, k)});
            }
        if (whole) continue;
        for (const auto& t : cap.triangles) {
            faces.add({at(t[0], 0), at(t[1], 0), at(t[2], 0)});
            faces.add({at(t[0], steps), at(t[2], steps), at(t[1], steps)});
        }
    }
    return closedMesh(std::move(points), faces);
}

// OpenSCAD's sgn_vdiff: the sign of |a| - |b|, 0 when they differ by at most 1e-5 of their
// mean (10 ppm, so that the choice does not depend on the part's size).
int compareLengths(Vec2 a, Vec2 b) {
    const double la = glm::length(a), lb = glm::length(b);
    return 2 * std::fabs(la - lb) * 1e5 > la + lb ? (la < lb ? -1 : 1) : 0;
}

}  // namespace

std::optional<std::vector<RegionPolygon>> chordRegion(const csg::Outline& outline,
                                                      const csg::Bounds2& box, double deviation) {
    std::vector<RegionPolygon> region;
    if (!(deviation > 0.0) || box.empty() || !regionOf(outline, box, deviation, region))
        return std::nullopt;
    return region;
}

// Corner k of a cap on layer j is point base + j corners + k.
std::optional<csg::Polyhedron> slicedExtrusionMesh(const std::vector<RegionPolygon>& region,
                                                   double z0, double z1, double twist, Vec2 scale,
                                                   int64_t slices, double capStraight) {
    if (region.empty() || slices < 1 || !(z1 > z0)) return std::nullopt;
    // Layer j's map, as extrudePolygon and add_slice compute it: the turn by -twist j / slices
    // (OpenSCAD's rotate_degrees, exact at multiples of 30 and 45 degrees), then the scale.
    struct Layer {
        glm::dmat2 map;  // column-major: map[column][row]
        double z;
        Vec2 scale;
        double turn;
    };
    std::vector<Layer> layers(size_t(slices) + 1);
    const double n = double(slices);
    for (int64_t j = 0; j <= slices; ++j) {
        Layer& layer = layers[size_t(j)];
        const double k = double(j);
        layer.turn = twist * k / n;
        layer.z = z0 + (z1 - z0) * k / n;
        layer.scale = Vec2(1 - (1 - scale.x) * k / n, 1 - (1 - scale.y) * k / n);
        const double c = openscadCosDegrees(-layer.turn), s = openscadSinDegrees(-layer.turn);
        layer.map = glm::dmat2(layer.scale.x * c, layer.scale.y * s,      // first column
                               -(layer.scale.x * s), layer.scale.y * c);  // second column
    }
    std::vector<Vec3> points;
    csg::PolygonFaces faces;
    for (const Polygon& polygon : region) {
        Cap cap;
        if (!cap.fill(polygon, capStraight)) return std::nullopt;
        const size_t corners = cap.corners.size();
        if (points.size() + corners * layers.size() > csg::Polyhedron::kMaxTriangles)
            return std::nullopt;
        const uint32_t base = uint32_t(points.size());
        for (const Layer& layer : layers)
            for (const Vec2& p : cap.corners) {
                const Vec2 q(layer.map[0][0] * p.x + layer.map[1][0] * p.y,
                             layer.map[0][1] * p.x + layer.map[1][1] * p.y);
                points.emplace_back(q, layer.z);
            }
        const auto at = [&](int64_t j, uint32_t k) { return base + uint32_t(j * corners) + k; };
        const auto planOf = [&](uint32_t index) { return Vec2(points[index]); };
        for (const auto& t : cap.triangles) {
            faces.add({at(0, t[0]), at(0, t[2]), at(0, t[1])});  // facing down
            if (scale.x != 0.0 && scale.y != 0.0)
                faces.add({at(slices, t[0]), at(slices, t[1]), at(slices, t[2])});
        }
        for (int64_t j = 0; j < slices; ++j) {
            const Layer &below = layers[size_t(j)], &above = layers[size_t(j) + 1];
            const bool anyZero = above.scale.x == 0.0 || above.scale.y == 0.0;
            const bool anyNonZero = above.scale.x != 0.0 || above.scale.y != 0.0;
            const bool turnsBack = above.turn <= below.turn;
            for (size_t loop = 0; loop < cap.loops.size(); ++loop) {
                const std::vector<uint32_t>& corner = cap.loops[loop];
                const bool flip = (loop > 0) != turnsBack;  // loop 0 is the outer contour
                for (size_t i = 1, m = corner.size(); i <= m; ++i) {
                    const uint32_t p1 = at(j, corner[i - 1]), c1 = at(j, corner[i % m]);
                    const uint32_t p2 = at(j + 1, corner[i - 1]), c2 = at(j + 1, corner[i % m]);
                    const int sign =
                        compareLengths(planOf(p1) - planOf(c2), planOf(c1) - planOf(p2));
                    const bool splitFirst = sign == -1 || (sign == 0 && !flip);
                    const bool second = !anyZero || (anyNonZero && planOf(p2) != planOf(c2));
                    if (splitFirst != anyZero) {
                        faces.add({p1, c2, c1});
                        if (second) faces.add({c2, p1, p2});
                    } else {
                        faces.add({p1, p2, c1});
                        if (second) faces.add({p2, c2, c1});
                    }
                }
            }
        }
        if (faces.size() > csg::Polyhedron::kMaxTriangles) return std::nullopt;
    }
    return closedMesh(std::move(points), faces, /*manifold=*/false);
}

std::optional<csg::Polyhedron> facetedRevolutionMesh(const std::vector<RegionPolygon>& region,
                                                     double start, double degrees,
                                                     int64_t sections) {
    if (region.empty() || sections < 1 || size_t(sections) > kMaxRevolutionPoints ||
        !(degrees > 0.0) || degrees > 360.0)
        return std::nullopt;
    const bool whole = degrees == 360.0;
    std::vector<Vec2> turn(size_t(whole ? sections : sections + 1));
    for (size_t k = 0; k < turn.size(); ++k) {
        const double a = start + degrees * double(k) / double(sections);
        turn[k] = Vec2(cosDegrees(a), sinDegrees(a));
    }
    return revolutionOf(region, turn, whole);
}

namespace {

// Calls visit(contour) for each outer contour and hole of the region, in order.
template <class Region, class Visit>
void forEachContour(Region& region, Visit&& visit) {
    for (auto& polygon : region) {
        visit(polygon.outer);
        for (auto& hole : polygon.holes) visit(hole);
    }
}

// The contour with each edge a -> b cut into `pieces` equal pieces (1 leaves it whole).
void cutEdges(std::vector<Vec2>& contour, const double* pieces) {
    std::vector<Vec2> cut;
    for (size_t i = 0, m = contour.size(); i < m; ++i) {
        const Vec2 a = contour[i], b = contour[(i + 1) % m];
        cut.push_back(a);
        for (double k = 1.0; k < pieces[i]; ++k) cut.push_back(a + (b - a) * (k / pieces[i]));
    }
    contour = std::move(cut);
}

// One outline edge's share of a sliced side: its length L and bounds J >= |S_ll . N| and K >=
// |S_lp . N| over it (N the side's unit normal; below).
struct EdgeBounds {
    double length, J, K;
};

// A twisted or unevenly scaled extrusion's mesh. Its side through the outline edge a -> b is
// S(l, p) = M(l) (a + p e) at height z0 + l h, e the edge's unit direction, p the length along
// it, M(l) = D(l) R(-w l), D(l) = diag(1 + (sx - 1) l, 1 + (sy - 1) l), w the twist in radians:
// linear in p. A slice of dl and a piece of length q of the edge make two triangles through four
// points of S; to second order they stand off S by at most |S_ll . N| dl^2 / 8 (as a chord
// misses an arc) plus |S_lp . N| dl q / 4 (the quad's twist: x y on the unit square's two
// triangles misses by 1/4), S_pp being 0. Only the parts along the normal N count: what S - I
// has along the side moves a point within it, which changes its distance to S only at the next
// order (and the export measures the mesh it keeps).
//   - Twist alone (D = 1): with q(p) = a + p e, S_ll = (-w^2 R q, 0), S_lp = (-w R J e, 0) (J the
//     quarter turn) and N = (h R J^T e, -w e . q) / n, n = sqrt(h^2 + w^2 (e . q)^2), so
//     |S_ll . N| = w^2 h |a x e| / n and |S_lp . N| = w h / n, n taken at the smallest |e . q|
//     on the edge. An edge along a radius far from the axis sweeps a steep helicoid whose normal
//     is nearly vertical: Debian's example020 spring, whose radial edges stand 90 from the axis
//     under 1 500 degrees, needs ~24 times fewer pieces on them than the whole second derivative
//     says.
//   - A twist and one scale s (D = sigma(l) = 1 + k l, k = s - 1): with g = R q and f = R e,
//     S_ll = (-2 k w J g - sigma w^2 g, 0), S_lp = (k f - sigma w J f, 0) and S_l x S_p =
//     (h sigma J f, sigma (k q x e + w sigma q . e)), whose length n is at least h sigma, so
//     |S_ll . N| = h sigma |2 k w q . e + sigma w^2 q x e| / n <= 2 |k| w max |q . e| +
//     v w^2 |a x e| and |S_lp . N| = h sigma^2 w / n <= v w, with v = max(1, s): the scale's
//     own rate drops out of K, and J counts the edge's reach along itself and its distance from
//     the axis instead of the outline's largest radius twice (a twisted pyramid's sides).
//   - Two scales, or one without a twist: with u = max |s_i - 1|, v = max(1, sx, sy) and rho the
//     outline's largest radius, |S_ll| = |(2 D' R' + D R'') q| <= (2 u w + v w^2) rho, and
//     |S_lp| = |(D' R + D R') e| <= |D' e| + v w without a twist, u + v w with one: the whole
//     derivatives, as bounds of their normal parts (with sx != sy the normal's length can
//     vanish faster than S_lp . (J D f) where a scale reaches 0).
// Slices are shared by all edges, pieces are per edge: n slices (dl = 1 / n) leave each edge
// pieces no longer than 4 (s - J dl^2 / 8) / (K dl), for its share s of the deviation. More
// slices leave more of s to the pieces, so the count of triangles, 2 n per corner on the sides
// and the caps', is least at some n past the fewest that keep s - J dl^2 / 8 > 0 on every edge:
// n is tried upward from there until every edge is whole (more slices then only add triangles),
// at most kSliceSearch times. The chords take half the deviation when the outline has curves,
// divided by v (a section is at most v times the outline).
std::optional<csg::Polyhedron> slicedToDeviation(const csg::Extrusion& e, double deviation) {
    constexpr double kSliceSearch = 256.0;
    const Vec2 grow = e.scale - Vec2(1.0);  // D'
    const double u = std::max(std::abs(grow.x), std::abs(grow.y));
    const double v = std::max({1.0, e.scale.x, e.scale.y});
    const double w = std::abs(e.twist) * std::numbers::pi / 180.0;
    const double h = e.z1 - e.z0;
    const double share = csg::straightEdged(*e.outline) ? deviation : 0.5 * deviation;
    std::vector<Polygon> region;
    if (!regionOf(*e.outline, e.box, 0.5 * deviation / v, region)) return std::nullopt;
    double rho = 0.0, size = 0.0;
    size_t contours = 0;
    forEachContour(region, [&](const std::vector<Vec2>& contour) {
        ++contours;
        for (const Vec2& p : contour) {
            rho = std::max(rho, glm::length(p));
            size = std::max({size, std::abs(p.x), std::abs(p.y)});
        }
    });
    std::vector<EdgeBounds> edges;
    double jMost = 0.0;
    forEachContour(region, [&](const std::vector<Vec2>& contour) {
        for (size_t i = 0, m = contour.size(); i < m; ++i) {
            const Vec2 a = contour[i], b = contour[(i + 1) % m];
            const double length = glm::length(b - a);
            const Vec2 unit = (b - a) / length;
            EdgeBounds bounds{length, 0.0, 0.0};
            const double along = glm::dot(unit, a), far = along + length;
            const double cross = std::abs(a.x * unit.y - a.y * unit.x);
            if (grow == Vec2(0.0)) {
                const double nearest =
                    along > 0.0 || far < 0.0 ? std::min(std::abs(along), std::abs(far)) : 0.0;
                const double n = std::sqrt(h * h + w * w * nearest * nearest);
                bounds.J = w * w * h * cross / n;
                bounds.K = w * h / n;
            } else if (grow.x == grow.y && w > 0.0) {
                const double reach = std::max(std::abs(along), std::abs(far));
                bounds.J = 2.0 * w * u * reach + v * w * w * cross;
                bounds.K = v * w;
            } else {
                bounds.J = (2.0 * u * w + v * w * w) * rho;
                bounds.K = (w == 0.0 ? glm::length(grow * unit) : u) + v * w;
            }
            jMost = std::max(jMost, bounds.J);
            edges.push_back(bounds);
        }
    });
    // The pieces of every edge under n slices (in `pieces`, their sum in `corners`) and the
    // triangles they make; +inf past kMaxExtrusionMeshCorners corners.
    std::vector<double> pieces(edges.size());
    double corners = 0.0;
    const auto trianglesAt = [&](double n) {
        corners = 0.0;
        for (size_t i = 0; i < edges.size(); ++i) {
            const EdgeBounds& b = edges[i];
            const double rest = share - b.J / (8.0 * n * n);
            const double longest = b.K > 0.0 ? 4.0 * rest * n / b.K : csg::kInfinity;
            pieces[i] = std::max(1.0, std::ceil(b.length / longest));
            corners += pieces[i];
            if (!(corners <= double(kMaxExtrusionMeshCorners))) return csg::kInfinity;
        }
        return 2.0 * n * corners + 2.0 * (corners - 2.0 * double(contours));
    };
    const double fewest = std::floor(std::sqrt(jMost / (8.0 * share))) + 1.0;
    // Declined before any search when the fewest slices already make too large a mesh (a
    // billion-degree twist).
    if (!(fewest * double(edges.size()) <= double(csg::Polyhedron::kMaxTriangles)))
        return std::nullopt;
    double slices = fewest, best = trianglesAt(fewest);
    for (double n = fewest + 1.0; n < fewest + kSliceSearch; ++n) {
        // Every edge whole at the last n tried: more slices only add triangles.
        if (corners == double(edges.size())) break;
        const double triangles = trianglesAt(n);
        if (triangles < best) best = triangles, slices = n;
    }
    if (!std::isfinite(best)) return std::nullopt;
    trianglesAt(slices);  // the pieces of the count chosen
    // Each corner makes a point per layer; the mesh may have no more than a polyhedron.
    if (!((slices + 1.0) * corners <= double(csg::Polyhedron::kMaxTriangles))) return std::nullopt;
    size_t first = 0;
    forEachContour(region, [&](std::vector<Vec2>& contour) {
        const size_t m = contour.size();
        cutEdges(contour, pieces.data() + first);
        first += m;
    });
    return slicedExtrusionMesh(region, e.z0, e.z1, e.twist, e.scale, int64_t(slices),
                               csg::tol::kCutPointStraightRel * size);
}

}  // namespace

std::optional<csg::Polyhedron> extrusionMesh(const csg::Extrusion& e, double deviation,
                                             csg::FacetFit fit) {
    using Kind = csg::Extrusion::Kind;
    if (!e.outline || !(deviation > 0.0) || e.box.empty()) return std::nullopt;
    std::vector<Polygon> region;
    if (e.kind == Kind::Linear) {
        if (!std::isfinite(e.z0) || !std::isfinite(e.z1)) return std::nullopt;
        if (e.twisted || e.twist != 0.0 || e.scale.x != e.scale.y)
            return slicedToDeviation(e, deviation);
        if (!(e.scale.x > 0.0)) return std::nullopt;
        // The chords stand `scale` times as far off the curve at the top as at the bottom.
        const double scale = e.scale.x;
        if (!regionOf(*e.outline, e.box, deviation / std::max(1.0, scale), region))
            return std::nullopt;
        return prismOf(region, e.z0, e.z1, scale);
    }
    if (e.kind == Kind::Rotate) {
        // A leaf reaching into x < 0 revolves only its part in x >= 0: the grid meshes it.
        if (e.box.lo.x < 0.0) return std::nullopt;
        // Half the deviation for the profile's chords, half for the meridians' (the sagitta of
        // a step at the largest radius); all of it for the meridians' when the profile has no
        // curve (about 1 / sqrt(2) of the steps).
        const double profileShare = csg::straightEdged(*e.outline) ? 0.0 : 0.5;
        if (!regionOf(*e.outline, e.box, 0.5 * deviation, region)) return std::nullopt;
        const double reach = std::max(std::abs(e.box.lo.x), std::abs(e.box.hi.x));
        const double angle = std::numbers::pi / 180.0 * e.angle;
        const double meridians = (1.0 - profileShare) * deviation;
        const bool whole = e.angle >= 360.0;
        const int64_t least = whole ? 3 : 1;
        int64_t steps = std::max(csg::chordSteps(reach, angle, meridians), least);
        // Balanced: every ring scaled out about the axis (csg::facetFitScale, c the cosine of
        // half a step). The fewest steps whose largest ring stands within the share so,
        // counting up from the chord rule at twice it (c < 1 makes that one short by a hair at
        // most); none beyond what a revolution may have.
        double scale = 1.0;
        if (fit == csg::FacetFit::Balanced) {
            scale = 0.0;
            for (steps = std::max(csg::chordSteps(reach, angle, 2.0 * meridians), least);
                 size_t(steps) <= kMaxRevolutionPoints; ++steps) {
                scale = csg::facetFitScale(fit, std::cos(0.5 * angle / double(steps)), reach,
                                           meridians);
                if (scale > 0.0) break;
            }
            if (!(scale > 0.0)) return std::nullopt;
        }
        std::vector<Vec2> turn(size_t(whole ? steps : steps + 1));
        for (size_t k = 0; k < turn.size(); ++k) {
            const double a = angle * double(k) / double(steps);
            turn[k] = scale * Vec2(std::cos(a), std::sin(a));
        }
        return revolutionOf(region, turn, whole);
    }
    return std::nullopt;
}

}  // namespace io
