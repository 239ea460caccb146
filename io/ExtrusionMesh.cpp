#include "io/ExtrusionMesh.h"

#include <clipper.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "csg/derived/Flatten2D.h"
#include "csg/mesh/EarClip.h"

namespace io {

namespace {

using csg::Vec2;
using csg::Vec3;

// Clipper's integers hold the chords' corners on a grid of 2^-kGridBits of the outline's size (a
// power of two, so the way there and back is exact but for the rounding to an integer), and
// every contour it returns is cleaned of corners within 1.415 steps of their neighbours or of
// the line through them (Clipper's CleanPolygon, as OpenSCAD cleans its polygons). Why 28:
// a step of 3.7e-9 of the size is above the exact boundary's weld distance
// (tol::kPolyBoundaryWeldRel, 1e-9), so no two corners it keeps apart are welded there, and
// the corners a projection leaves a few ulps apart, whose side faces have no area to classify,
// become one; it moves a corner by 2e-9 of the size, far below any tolerance an export asks.
constexpr int kGridBits = 28;
constexpr double kCleanDistance = 1.415;

// The two caps and the sides of the prism over the region, built face by face.
struct Prism {
    std::vector<Vec3> points;
    csg::PolygonFaces faces;
    double z0, z1, scale;

    // The corner at p, at the bottom (its index) and at the top (its index + 1).
    uint32_t corner(Vec2 p) {
        points.emplace_back(p, z0);
        points.emplace_back(scale * p, z1);
        return uint32_t(points.size() - 2);
    }
};

// Adds the filled region of outer (counter-clockwise) minus its holes (clockwise, inside it):
// its caps, ear-clipped, and its contours' sides, facing out of the region.
bool addPolygon(const ClipperLib::PolyNode& outer, double unit, Prism& prism) {
    std::vector<Vec2> corners;
    std::vector<uint32_t> ids;
    std::vector<std::vector<uint32_t>> loops;  // the outer, then the holes
    const auto addLoop = [&](const ClipperLib::Path& path) {
        std::vector<uint32_t>& loop = loops.emplace_back();
        for (const ClipperLib::IntPoint& q : path) {
            const Vec2 p(double(q.X) * unit, double(q.Y) * unit);
            loop.push_back(uint32_t(corners.size()));
            corners.push_back(p);
            ids.push_back(prism.corner(p));
        }
    };
    ClipperLib::Path contour;
    ClipperLib::CleanPolygon(outer.Contour, contour, kCleanDistance);
    if (contour.size() < 3) return true;  // nothing left of it (its holes are smaller still)
    addLoop(contour);
    for (const ClipperLib::PolyNode* hole : outer.Childs) {
        ClipperLib::CleanPolygon(hole->Contour, contour, kCleanDistance);
        if (contour.size() >= 3) addLoop(contour);
    }
    const std::vector<std::vector<uint32_t>> holes(loops.begin() + 1, loops.end());
    std::vector<std::array<uint32_t, 3>> triangles;
    if (!csg::earClip(corners, loops[0], holes, 0.0, triangles)) return false;
    for (const auto& t : triangles) {
        prism.faces.add({ids[t[0]], ids[t[2]], ids[t[1]]});              // the bottom, down
        prism.faces.add({ids[t[0]] + 1, ids[t[1]] + 1, ids[t[2]] + 1});  // the top, up
    }
    // Clipper winds outers counter-clockwise and holes clockwise: the region is on the left of
    // every edge, so a quad from edge a -> b up faces out of it.
    for (const std::vector<uint32_t>& loop : loops)
        for (size_t k = 0, m = loop.size(); k < m; ++k) {
            const uint32_t a = ids[loop[k]], b = ids[loop[(k + 1) % m]];
            prism.faces.add({a, b, b + 1, a + 1});
        }
    return true;
}

}  // namespace

std::optional<csg::Polyhedron> straightExtrusionMesh(const csg::Extrusion& e, double deviation) {
    using Kind = csg::Extrusion::Kind;
    if (e.kind != Kind::Linear || e.twisted || e.twist != 0.0 || e.scale.x != e.scale.y ||
        !(e.scale.x > 0.0) || !std::isfinite(e.z0) || !std::isfinite(e.z1) || !e.outline ||
        !(deviation > 0.0) || e.box.empty())
        return std::nullopt;
    const double scale = e.scale.x;
    const double size = std::max({std::abs(e.box.lo.x), std::abs(e.box.lo.y), std::abs(e.box.hi.x),
                                  std::abs(e.box.hi.y), std::numeric_limits<double>::min()});
    const int sizeExponent = std::ilogb(size) + 1;  // size < 2^sizeExponent
    const double toGrid = std::ldexp(1.0, kGridBits - sizeExponent);
    const double unit = std::ldexp(1.0, sizeExponent - kGridBits);

    // The segments chained into closed walks at their shared ends (an outline's neighbouring
    // segments share the very same doubles; its segments may come in any order), one Clipper
    // path each. Where walks touch, which segment comes next does not matter: every
    // decomposition of the directed segments into closed walks has the same winding numbers.
    // A walk that does not close (a dangling end) declines.
    const std::vector<csg::Segment2>& segments = e.outline->segments;
    const auto before = [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
    std::vector<uint32_t> byStart(segments.size());
    for (uint32_t i = 0; i < byStart.size(); ++i) byStart[i] = i;
    std::sort(byStart.begin(), byStart.end(), [&](uint32_t a, uint32_t b) {
        return before(segments[a].start(), segments[b].start());
    });
    std::vector<bool> used(segments.size(), false);
    const auto nextFrom = [&](Vec2 p) -> int64_t {
        auto it = std::lower_bound(byStart.begin(), byStart.end(), p, [&](uint32_t k, Vec2 q) {
            return before(segments[k].start(), q);
        });
        for (; it != byStart.end() && segments[*it].start() == p; ++it)
            if (!used[*it]) return *it;
        return -1;
    };
    // The chords stand `scale` times as far off the curve at the top as at the bottom.
    const double chordDeviation = deviation / std::max(1.0, scale);
    ClipperLib::Paths paths;
    std::vector<Vec2> points;
    size_t corners = 0;
    for (uint32_t first = 0; first < segments.size(); ++first) {
        if (used[first]) continue;
        ClipperLib::Path& path = paths.emplace_back();
        bool closed = false;
        for (int64_t k = first; k >= 0 && !closed; k = nextFrom(segments[size_t(k)].finish())) {
            used[size_t(k)] = true;
            points.clear();
            csg::appendChordPoints(segments[size_t(k)], chordDeviation, points);
            corners += points.size();
            if (corners > kMaxExtrusionMeshCorners) return std::nullopt;
            for (const Vec2& p : points)
                path.push_back({ClipperLib::cInt(std::llround(p.x * toGrid)),
                                ClipperLib::cInt(std::llround(p.y * toGrid))});
            closed = segments[size_t(k)].finish() == segments[first].start();
        }
        if (!closed) return std::nullopt;
    }

    // The region by the outline's fill rule, as outer contours with their holes.
    ClipperLib::Clipper clipper;
    clipper.StrictlySimple(true);
    ClipperLib::PolyTree tree;
    try {
        clipper.AddPaths(paths, ClipperLib::ptSubject, true);
        const ClipperLib::PolyFillType fill = e.outline->rule == csg::FillRule::EvenOdd
                                                  ? ClipperLib::pftEvenOdd
                                                  : ClipperLib::pftNonZero;
        if (!clipper.Execute(ClipperLib::ctUnion, tree, fill, fill)) return std::nullopt;
    } catch (const ClipperLib::clipperException&) {
        return std::nullopt;
    }

    Prism prism{{}, {}, e.z0, e.z1, scale};
    std::vector<const ClipperLib::PolyNode*> pending(tree.Childs.begin(), tree.Childs.end());
    while (!pending.empty()) {
        const ClipperLib::PolyNode* outer = pending.back();
        pending.pop_back();
        if (!addPolygon(*outer, unit, prism)) return std::nullopt;
        // An island inside a hole is an outer of its own.
        for (const ClipperLib::PolyNode* hole : outer->Childs)
            pending.insert(pending.end(), hole->Childs.begin(), hole->Childs.end());
    }
    if (prism.faces.size() == 0) return std::nullopt;
    csg::Polyhedron mesh = csg::Polyhedron::make(std::move(prism.points), prism.faces);
    if (mesh.invalidReason() || !mesh.edges().manifold()) return std::nullopt;
    return mesh;
}

}  // namespace io
