#include "csg/section/LeafMesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <stdexcept>

#include "csg/Scene.h"
#include "csg/derived/Flatten2D.h"
#include "csg/mesh/Tessellate.h"

namespace csg {

namespace {

void addVertex(WorldMesh& out, const Mat4& m, const Vec3& p) {
    const Vec3 v = transformPoint(m, p);
    out.vertices.push_back(v);
    out.box.extend(v);
}

// A polygon of corner indices as a fan from its first corner, one face: exact for the convex
// faces of a box or a convex polytope.
void addFan(WorldMesh& out, uint32_t offset, std::span<const uint32_t> face) {
    out.faceStarts.push_back(uint32_t(out.triangles.size()));
    for (size_t k = 1; k + 1 < face.size(); ++k)
        out.triangles.push_back({offset + face[0], offset + face[k], offset + face[k + 1]});
}

void addBox(WorldMesh& out, const Box& box, const Mat4& m) {
    // Corner i has x from bit 0, y from bit 1, z from bit 2 (0: lo, 1: hi).
    for (uint32_t i = 0; i < 8; ++i)
        addVertex(out, m,
                  Vec3(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                       i & 4 ? box.hi.z : box.lo.z));
    static constexpr uint32_t kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                              {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const auto& face : kFaces) addFan(out, 0, face);
    out.faceStarts.push_back(uint32_t(out.triangles.size()));
}

void addPolytope(WorldMesh& out, const ConvexPolytope& polytope, const Mat4& m) {
    const ConvexPolytopeData& data = *polytope.data;
    for (const Vec3& v : data.vertices) addVertex(out, m, v);
    for (size_t f = 0; f + 1 < data.faceStarts.size(); ++f)
        addFan(out, 0,
               std::span<const uint32_t>(data.faceVertices)
                   .subspan(data.faceStarts[f], data.faceStarts[f + 1] - data.faceStarts[f]));
    out.faceStarts.push_back(uint32_t(out.triangles.size()));
}

void addPolyhedron(WorldMesh& out, const Polyhedron& mesh, const Mat4& m) {
    const PolyhedronData& data = *mesh.data;
    for (const Vec3& v : data.vertices) addVertex(out, m, v);
    out.triangles = data.triangles;
}

// Whether a linear_extrude is a prism, a frustum or a pyramid over its outline: no twist and
// one scale for both axes (so each wall is a ruled surface whose every section is the
// outline's, scaled), by the even-odd rule (a fan over the cap is then the cap by crossing
// parity; a nonzero outline may wind twice).
bool isUprightPrism(const Extrusion& e) {
    return e.kind == Extrusion::Kind::Linear && e.twist == 0.0 && e.scale.x == e.scale.y &&
           e.outline->rule == FillRule::EvenOdd;
}

// ... and a polyhedron: every segment straight, so each wall is a planar trapezoid (or a
// triangle to an apex).
bool isStraightPrism(const Extrusion& e) {
    return isUprightPrism(e) && straightEdged(*e.outline);
}

// The prism (or frustum, or pyramid at scale 0) over an outline of straight segments (the
// extrusion's own, or its chords): the bottom outline at z0, the top one scaled by s at z1, a
// wall of two triangles per segment and each cap a fan from one outline vertex c. The fan's
// triangles overlap where the outline is not convex from c, but their even-odd sum is the
// cap: a point q lies in the triangle of segment ab exactly when the ray from q away from c
// crosses ab, so the triangles over q are as many as that ray's crossings of the outline, odd
// exactly inside. Sections and shadows read faces so (LeafMesh.h).
void addPrism(WorldMesh& out, const Extrusion& e, const std::vector<std::array<Vec2, 2>>& lines,
              const Mat4& m) {
    // Corners welded by their exact coordinates: segments that meet share the very same
    // doubles (Outline.h), so the walls share edges and the sections' loops close.
    std::map<std::pair<double, double>, uint32_t> index;
    std::vector<Vec2> corners;
    auto corner = [&](Vec2 p) {
        const auto [it, added] = index.try_emplace({p.x, p.y}, uint32_t(corners.size()));
        if (added) corners.push_back(p);
        return it->second;
    };
    std::vector<std::array<uint32_t, 2>> edges;
    for (const auto& [p, q] : lines) {
        const uint32_t a = corner(p), b = corner(q);
        if (a != b) edges.push_back({a, b});
    }
    if (edges.empty()) return;
    const uint32_t n = uint32_t(corners.size());
    const double s = e.scale.x;
    for (const Vec2& p : corners) addVertex(out, m, Vec3(p, e.z0));
    const bool apex = s == 0.0;
    if (apex)
        addVertex(out, m, Vec3(0.0, 0.0, e.z1));
    else
        for (const Vec2& p : corners) addVertex(out, m, Vec3(s * p, e.z1));
    auto top = [&](uint32_t i) { return apex ? n : n + i; };
    // Walls: a planar trapezoid per segment (its top edge is its bottom edge scaled).
    for (const auto& [a, b] : edges) {
        out.faceStarts.push_back(uint32_t(out.triangles.size()));
        out.triangles.push_back({a, b, top(b)});
        if (!apex) out.triangles.push_back({a, top(b), top(a)});
    }
    // Caps: fans from the first corner; a triangle on a segment through that corner has no
    // area and adds nothing to the parity, so it is left out.
    for (const bool upper : {false, true}) {
        if (upper && apex) break;
        out.faceStarts.push_back(uint32_t(out.triangles.size()));
        const uint32_t pivot = upper ? top(0) : 0;
        for (const auto& [a, b] : edges) {
            if (a == 0 || b == 0) continue;
            out.triangles.push_back(upper ? std::array<uint32_t, 3>{pivot, top(a), top(b)}
                                          : std::array<uint32_t, 3>{pivot, a, b});
        }
        if (out.faceStarts.back() == out.triangles.size()) out.faceStarts.pop_back();
    }
    out.faceStarts.push_back(uint32_t(out.triangles.size()));
}

// Segments per turn that keep a circle of radius r within t of its inscribed polygon (the
// sagitta r (1 - cos(pi / n)) <= t: csg::chordSteps), at least 8 and at most 4096 (t >= 3e-7 r).
int segmentsFor(double r, double t) {
    return int(std::clamp<int64_t>(chordSteps(r, 2.0 * kPi, t), 8, 4096));
}

// A closed surface of revolution about z through the profile points (rho, z), first and last
// on the axis or not: rings of n vertices, a pole vertex where rho = 0, and a fan cap from
// the axis where an end ring has rho > 0.
void addRevolved(WorldMesh& out, const Mat4& m, const std::vector<Vec2>& profile, int n,
                 double turn0 = 0.0) {
    std::vector<uint32_t> ringStart;
    for (const Vec2& p : profile) {
        ringStart.push_back(uint32_t(out.vertices.size()));
        const int count = p.x > 0.0 ? n : 1;
        for (int j = 0; j < count; ++j) {
            const double a = turn0 + 2.0 * kPi * j / n;
            addVertex(out, m, Vec3(p.x * std::cos(a), p.x * std::sin(a), p.y));
        }
    }
    auto at = [&](size_t ring, int j) {
        return ringStart[ring] + (profile[ring].x > 0.0 ? uint32_t(j % n) : 0u);
    };
    for (size_t k = 0; k + 1 < profile.size(); ++k)
        for (int j = 0; j < n; ++j) {
            const uint32_t a = at(k, j), b = at(k, j + 1), c = at(k + 1, j + 1), d = at(k + 1, j);
            if (a != b) out.triangles.push_back({a, b, c});
            if (c != d) out.triangles.push_back({a, c, d});
        }
    // Caps on the axis for open ends.
    for (size_t end : {size_t(0), profile.size() - 1}) {
        if (!(profile[end].x > 0.0)) continue;
        const uint32_t centre = uint32_t(out.vertices.size());
        addVertex(out, m, Vec3(0.0, 0.0, profile[end].y));
        for (int j = 0; j < n; ++j) out.triangles.push_back({centre, at(end, j), at(end, j + 1)});
    }
}

// The largest factor by which m's linear part stretches a length (its Frobenius norm bounds
// the spectral norm from above).
double stretchOf(const Mat4& m) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) sum += glm::dot(Vec3(m[c]), Vec3(m[c]));
    return std::sqrt(sum);
}

// Inscribed polyhedra of the quadrics and the torus, within t (local units) of the surface:
// each of the two directions of a grid cell takes half of t.
bool addCurved(WorldMesh& out, const Primitive& shape, const Mat4& m, double t) {
    if (const auto* sphere = std::get_if<Sphere>(&shape)) {
        const double r = sphere->radius;
        const int n = segmentsFor(r, 0.5 * t), rings = std::max(4, n / 2);
        std::vector<Vec2> profile;
        for (int i = 0; i <= rings; ++i) {
            const double phi = kPi * i / rings;
            profile.push_back(i == 0 || i == rings ? Vec2(0.0, i == 0 ? -r : r)
                                                   : Vec2(r * std::sin(phi), -r * std::cos(phi)));
        }
        addRevolved(out, m, profile, n);
        return true;
    }
    if (const auto* cylinder = std::get_if<Cylinder>(&shape)) {
        const int n = segmentsFor(std::max(cylinder->r1, cylinder->r2), t);
        addRevolved(out, m, {Vec2(cylinder->r1, 0.0), Vec2(cylinder->r2, cylinder->height)}, n);
        return true;
    }
    if (const auto* torus = std::get_if<Torus>(&shape)) {
        const double big = torus->majorRadius, small = torus->minorRadius;
        const int nu = segmentsFor(big + small, 0.5 * t), nv = segmentsFor(small, 0.5 * t);
        // Rings of the tube: each ring v a circle about z, joined ring to ring like a
        // revolution whose profile closes on itself.
        const uint32_t first = uint32_t(out.vertices.size());
        for (int i = 0; i < nv; ++i) {
            const double v = 2.0 * kPi * i / nv;
            const double rho = big + small * std::cos(v), z = small * std::sin(v);
            for (int j = 0; j < nu; ++j) {
                const double a = 2.0 * kPi * j / nu;
                addVertex(out, m, Vec3(rho * std::cos(a), rho * std::sin(a), z));
            }
        }
        auto at = [&](int i, int j) { return first + uint32_t((i % nv) * nu + (j % nu)); };
        for (int i = 0; i < nv; ++i)
            for (int j = 0; j < nu; ++j) {
                out.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
                out.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
            }
        return true;
    }
    return false;
}

}  // namespace

bool isPolyhedral(const Primitive& shape) {
    if (const auto* e = std::get_if<Extrusion>(&shape)) return isStraightPrism(*e);
    return std::holds_alternative<Box>(shape) || std::holds_alternative<ConvexPolytope>(shape) ||
           std::holds_alternative<Polyhedron>(shape);
}

WorldMesh leafMesh(const Primitive& shape, const Mat4& worldFromLocal, double tolerance) {
    WorldMesh out;
    if (const auto* box = std::get_if<Box>(&shape)) {
        addBox(out, *box, worldFromLocal);
        return out;
    }
    if (const auto* polytope = std::get_if<ConvexPolytope>(&shape)) {
        addPolytope(out, *polytope, worldFromLocal);
        return out;
    }
    if (const auto* mesh = std::get_if<Polyhedron>(&shape)) {
        addPolyhedron(out, *mesh, worldFromLocal);
        return out;
    }
    if (const auto* e = std::get_if<Extrusion>(&shape); e && e->kind == Extrusion::Kind::Plane)
        throw std::invalid_argument("a 2-D shape has no bounded solid to project");
    if (const auto* e = std::get_if<Extrusion>(&shape); e && isUprightPrism(*e)) {
        // Its own walls when they are straight, else those of its outline's chords within the
        // tolerance (local units; the top's chords are scaled by s, the walls' in between).
        const double chordTolerance =
            tolerance / stretchOf(worldFromLocal) / std::max(1.0, e->scale.x);
        std::vector<std::array<Vec2, 2>> lines;
        std::vector<Vec2> points;
        bool chords = false;
        for (const Segment2& s : e->outline->segments) {
            if (s.kind == Segment2::Kind::Line) {
                lines.push_back({s.p[0], s.p[1]});
                continue;
            }
            chords = true;
            points.clear();
            appendChordPoints(s, chordTolerance, points);
            points.push_back(s.finish());
            for (size_t k = 0; k + 1 < points.size(); ++k)
                lines.push_back({points[k], points[k + 1]});
        }
        addPrism(out, *e, lines, worldFromLocal);
        if (chords) out.exact = false, out.error = tolerance;
        return out;
    }
    // Spheres, cylinders and tori: inscribed polyhedra fine enough, built directly (far
    // fewer triangles than the mesher's, for the same bound).
    if (addCurved(out, shape, worldFromLocal, tolerance / stretchOf(worldFromLocal))) {
        out.exact = false;
        out.error = tolerance;
        return out;
    }
    // Mesh the leaf alone, in the frame asked for.
    const Scene scene = Scene::compile(transformed(worldFromLocal, leaf(shape)));
    TessellateOptions options;
    options.tolerance = tolerance;
    // The grid mesh: simplifying it costs several times the meshing, and Clipper sums up the
    // sections and shadows of its triangles anyway.
    options.simplify = false;
    TessellateResult meshed = tessellate(scene, options);
    out.exact = false;
    out.error = std::max(meshed.error.max, meshed.backError.max);
    out.vertices = std::move(meshed.mesh.positions);
    out.triangles = std::move(meshed.mesh.triangles);
    for (const Vec3& v : out.vertices) out.box.extend(v);
    return out;
}

}  // namespace csg
