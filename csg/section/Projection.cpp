// Plane sections and shadows of CSG trees by Clipper polygon booleans: see Projection.h for
// the method and why it is exact for polyhedral leaves.
#include "csg/section/Projection.h"

#include <polyclipping/clipper.hpp>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <variant>

#include "csg/Scene.h"
#include "csg/mesh/Tessellate.h"
#include "csg/section/LeafMesh.h"

namespace csg {

namespace {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

// Bits of the integer grid below the part's largest coordinate: Clipper takes coordinates up
// to 2^62 and multiplies them in 128 bits; 2^50 leaves room for sums and rounds a coordinate
// to 2^-50 of the extent, about what a double's own rounding does there.
constexpr int kGridBits = 50;

struct Grid {
    double scale = 1.0;
    IntPoint to(double x, double y) const {
        return IntPoint(ClipperLib::cInt(std::llround(x * scale)),
                        ClipperLib::cInt(std::llround(y * scale)));
    }
    Vec2 from(const IntPoint& p) const { return Vec2(double(p.X) / scale, double(p.Y) / scale); }
};

// The tree with every leaf a mesh in the root's frame.
struct FlatNode {
    Op op = Op::Leaf;
    int left = -1, right = -1;  // -1: the empty solid
    int leaf = -1;              // into Flat::leaves
    Bounds3 box;                // bottom-up: union hull, intersection overlap, difference left
    NodePtr source;             // for meshing a subtree as a whole
    Mat4 frame{1.0};            // root from source's parent frame
};

struct Flat {
    std::vector<FlatNode> nodes;
    std::vector<WorldMesh> leaves;
    int root = -1;
    double extent = 0.0;  // largest |coordinate| of any leaf vertex
    Grid grid;
    ProjectionResult* result = nullptr;
};

double tightDiagonal(const Primitive& shape, const Mat4& m) {
    const Bounds3 local = std::visit([](const auto& s) { return s.bounds(); }, shape);
    const Bounds3 world = transformBounds(m, local);
    if (!world.finite() || world.empty())
        throw std::invalid_argument(
            "a part with an unbounded solid (a half-space) has no "
            "bounded projection");
    return glm::length(world.hi - world.lo);
}

int flatten(const NodePtr& node, const Mat4& parent, Flat& flat) {
    if (!node) return -1;
    const Mat4 here = parent * node->parentFromNode;
    FlatNode out;
    out.op = node->op;
    out.source = node;
    out.frame = parent;
    if (node->op == Op::Leaf) {
        const double tolerance =
            isPolyhedral(node->primitive)
                ? 0.0
                : tol::kLeafMeshToleranceRel * tightDiagonal(node->primitive, here);
        WorldMesh mesh = leafMesh(node->primitive, here, tolerance);
        if (!mesh.exact) {
            flat.result->exact = false;
            ++flat.result->meshedLeaves;
            flat.result->meshError = std::max(flat.result->meshError, mesh.error);
        }
        out.box = mesh.box;
        for (const Vec3& v : mesh.vertices)
            flat.extent = std::max({flat.extent, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
        out.leaf = int(flat.leaves.size());
        flat.leaves.push_back(std::move(mesh));
    } else {
        out.left = flatten(node->left, here, flat);
        out.right = flatten(node->right, here, flat);
        const Bounds3 none;
        const Bounds3& l = out.left >= 0 ? flat.nodes[size_t(out.left)].box : none;
        const Bounds3& r = out.right >= 0 ? flat.nodes[size_t(out.right)].box : none;
        if (node->op == Op::Union) {
            out.box = l;
            out.box.extend(r);
        } else if (node->op == Op::Intersection) {
            out.box = Bounds3{glm::max(l.lo, r.lo), glm::min(l.hi, r.hi)};
        } else {
            out.box = l;
        }
    }
    flat.nodes.push_back(std::move(out));
    return int(flat.nodes.size() - 1);
}

Flat flattenTree(const NodePtr& root, const Mat4& frame, ProjectionResult& result) {
    Flat flat;
    flat.result = &result;
    flat.root = flatten(root, frame, flat);
    // 2^kGridBits units cover the extent (scale a power of two: exact to apply and undo).
    int exponent = 0;
    std::frexp(flat.extent > 0.0 ? flat.extent : 1.0, &exponent);
    flat.grid.scale = std::ldexp(1.0, kGridBits - exponent);
    return flat;
}

bool overlaps(const Bounds3& a, const Bounds3& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
           a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

Paths clip(ClipperLib::ClipType type, const Paths& a, const Paths& b,
           ClipperLib::PolyFillType fill = ClipperLib::pftNonZero) {
    ClipperLib::Clipper c;
    c.AddPaths(a, ClipperLib::ptSubject, true);
    c.AddPaths(b, ClipperLib::ptClip, true);
    Paths out;
    c.Execute(type, out, fill, fill);
    return out;
}

Paths unite(const Paths& a, const Paths& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return clip(ClipperLib::ctUnion, a, b);
}

// A plane n . x = c and the side its section is taken on (see Projection.h's notation).
struct CutPlane {
    Vec3 n;
    double c = 0.0;
    bool above = true;   // side +: vertices on the plane count as below it
    double onPlane = 0;  // |n . v - c| up to this counts as 0
    // Each leaf's section closed (both sides united) before the booleans, as OpenSCAD's
    // projection(cut = true) takes it; otherwise the booleans act on one side's sections.
    bool closedLeaves = false;
};

// The section of one mesh, as loops in x, y on the grid, normalised to non-overlapping
// polygons by the even-odd rule.
Paths sectionOf(const WorldMesh& mesh, const CutPlane& plane, const Grid& grid) {
    const size_t nv = mesh.vertices.size();
    std::vector<double> d(nv);
    std::vector<uint8_t> up(nv);
    for (size_t i = 0; i < nv; ++i) {
        double s = glm::dot(plane.n, mesh.vertices[i]) - plane.c;
        if (std::abs(s) <= plane.onPlane) s = 0.0;
        d[i] = s;
        up[i] = plane.above ? s > 0.0 : s >= 0.0;
    }
    // Segments between crossed edges, keyed by the edge's ends (lower index first).
    auto key = [](uint32_t a, uint32_t b) {
        return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
    };
    std::vector<std::pair<uint64_t, uint64_t>> segments;
    std::unordered_map<uint64_t, std::vector<uint32_t>> at;  // edge -> segments through it
    for (const auto& t : mesh.triangles) {
        const bool u0 = up[t[0]], u1 = up[t[1]], u2 = up[t[2]];
        if (u0 == u1 && u1 == u2) continue;
        uint64_t ends[2];
        int k = 0;
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = t[e], b = t[(e + 1) % 3];
            if (up[a] != up[b]) ends[k++] = key(a, b);
        }
        const uint32_t id = uint32_t(segments.size());
        segments.push_back({ends[0], ends[1]});
        at[ends[0]].push_back(id);
        at[ends[1]].push_back(id);
    }
    auto point = [&](uint64_t edge) {
        const uint32_t a = uint32_t(edge >> 32), b = uint32_t(edge & 0xffffffffu);
        Vec3 p;
        if (d[a] == 0.0)
            p = mesh.vertices[a];
        else if (d[b] == 0.0)
            p = mesh.vertices[b];
        else
            p = mesh.vertices[a] + (mesh.vertices[b] - mesh.vertices[a]) * (d[a] / (d[a] - d[b]));
        return grid.to(p.x, p.y);
    };
    // Chain: from each unused segment, walk through edges to unused segments until the loop
    // closes (every crossed edge of a closed mesh has an even number of segments).
    std::vector<uint8_t> used(segments.size(), 0);
    Paths loops;
    for (uint32_t s = 0; s < segments.size(); ++s) {
        if (used[s]) continue;
        used[s] = 1;
        Path loop{point(segments[s].first)};
        const uint64_t start = segments[s].first;
        uint64_t edge = segments[s].second;
        while (edge != start) {
            loop.push_back(point(edge));
            uint32_t next = UINT32_MAX;
            for (uint32_t candidate : at[edge])
                if (!used[candidate]) {
                    next = candidate;
                    break;
                }
            if (next == UINT32_MAX) break;  // an open mesh: the loop closes itself
            used[next] = 1;
            edge = segments[next].first == edge ? segments[next].second : segments[next].first;
        }
        if (loop.size() >= 3) loops.push_back(std::move(loop));
    }
    Paths out;
    ClipperLib::Clipper c;
    c.AddPaths(loops, ClipperLib::ptSubject, true);
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
    return out;
}

// The CSG of the leaves' sections on one side of the plane (or of their closed sections). With a
// window, leaves whose box misses it count as empty: right within the window, which is all the
// caller keeps.
Paths sectionOf(const Flat& flat, int node, const CutPlane& plane, const Bounds3* window) {
    if (node < 0) return {};
    const FlatNode& x = flat.nodes[size_t(node)];
    if (window && !overlaps(x.box, *window)) return {};
    if (x.op == Op::Leaf) {
        const WorldMesh& mesh = flat.leaves[size_t(x.leaf)];
        if (!plane.closedLeaves) return sectionOf(mesh, plane, flat.grid);
        CutPlane other = plane;
        other.above = !plane.above;
        return unite(sectionOf(mesh, plane, flat.grid), sectionOf(mesh, other, flat.grid));
    }
    Paths l = sectionOf(flat, x.left, plane, window);
    if (x.op != Op::Union && l.empty()) return {};
    Paths r = sectionOf(flat, x.right, plane, window);
    switch (x.op) {
        case Op::Union:
            return unite(l, r);
        case Op::Intersection:
            return r.empty() ? Paths{} : clip(ClipperLib::ctIntersection, l, r);
        default:
            return r.empty() ? l : clip(ClipperLib::ctDifference, l, r);
    }
}

// The section of the regularised solid: the CSG on each side, then their union.
Paths closedSection(const Flat& flat, int node, CutPlane plane, const Bounds3* window) {
    plane.above = true;
    Paths a = sectionOf(flat, node, plane, window);
    plane.above = false;
    return unite(a, sectionOf(flat, node, plane, window));
}

// The projected triangle, counter-clockwise, or empty when it has no area on the grid.
Path projected(const WorldMesh& mesh, const std::array<uint32_t, 3>& t, const Grid& grid) {
    Path p{grid.to(mesh.vertices[t[0]].x, mesh.vertices[t[0]].y),
           grid.to(mesh.vertices[t[1]].x, mesh.vertices[t[1]].y),
           grid.to(mesh.vertices[t[2]].x, mesh.vertices[t[2]].y)};
    const double area = ClipperLib::Area(p);
    if (area == 0.0) return {};
    if (area < 0.0) std::swap(p[1], p[2]);
    return p;
}

// Calls f(first, last) for each face of the mesh, triangles [first, last) (LeafMesh.h).
template <class F>
void forFaces(const WorldMesh& mesh, F&& f) {
    if (mesh.faceStarts.empty()) {
        for (uint32_t t = 0; t < mesh.triangles.size(); ++t) f(t, t + 1);
        return;
    }
    for (size_t k = 0; k + 1 < mesh.faceStarts.size(); ++k)
        f(mesh.faceStarts[k], mesh.faceStarts[k + 1]);
}

// The projection of a face: the even-odd sum of its projected triangles, outer curves
// counter-clockwise (so that faces can be summed by the nonzero rule); empty when it has no
// area on the grid (a vertical face).
Paths projectedFace(const WorldMesh& mesh, uint32_t first, uint32_t last, const Grid& grid) {
    Paths triangles;
    for (uint32_t t = first; t < last; ++t)
        if (Path p = projected(mesh, mesh.triangles[t], grid); !p.empty())
            triangles.push_back(std::move(p));
    if (triangles.size() <= 1) return triangles;
    Paths out;
    ClipperLib::Clipper c;
    c.AddPaths(triangles, ClipperLib::ptSubject, true);
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
    return out;
}

Paths leafShadow(const WorldMesh& mesh, const Grid& grid) {
    Paths faces;
    faces.reserve(mesh.triangles.size());
    forFaces(mesh, [&](uint32_t first, uint32_t last) {
        Paths face = projectedFace(mesh, first, last, grid);
        faces.insert(faces.end(), std::make_move_iterator(face.begin()),
                     std::make_move_iterator(face.end()));
    });
    Paths out;
    ClipperLib::Clipper c;
    c.AddPaths(faces, ClipperLib::ptSubject, true);
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return out;
}

void collectLeaves(const Flat& flat, int node, std::vector<int>& out) {
    if (node < 0) return;
    const FlatNode& x = flat.nodes[size_t(node)];
    if (x.op == Op::Leaf) return out.push_back(x.leaf);
    collectLeaves(flat, x.left, out);
    collectLeaves(flat, x.right, out);
}

Bounds3 faceBox(const WorldMesh& mesh, uint32_t first, uint32_t last) {
    Bounds3 b;
    for (uint32_t t = first; t < last; ++t)
        for (uint32_t i : mesh.triangles[t]) b.extend(mesh.vertices[i]);
    return b;
}

// The shadow of an intersection or difference by its faces (Projection.h), or nothing when
// that would cost more than kMaxFaceWork.
std::optional<Paths> faceShadow(const Flat& flat, int node) {
    std::vector<int> leaves;
    collectLeaves(flat, node, leaves);
    uint64_t work = 0;
    for (int f : leaves) {
        const WorldMesh& mesh = flat.leaves[size_t(f)];
        forFaces(mesh, [&](uint32_t first, uint32_t last) {
            const Bounds3 box = faceBox(mesh, first, last);
            for (int g : leaves)
                if (overlaps(box, flat.leaves[size_t(g)].box))
                    work += flat.leaves[size_t(g)].triangles.size() + 1;
        });
        if (work > kMaxFaceWork) return std::nullopt;
    }
    Paths pieces;
    const double onPlane = tol::kOnFacePlaneRel * std::max(flat.extent, 1e-300);
    for (int f : leaves) {
        const WorldMesh& mesh = flat.leaves[size_t(f)];
        // The piece of triangles [first, last), which lie in one plane.
        auto addPiece = [&](uint32_t first, uint32_t last, const CutPlane& plane) {
            const Paths face = projectedFace(mesh, first, last, flat.grid);
            if (face.empty()) return;  // vertical: no area in the shadow
            Bounds3 window = faceBox(mesh, first, last);
            const Paths section = closedSection(flat, node, plane, &window);
            if (section.empty()) return;
            Paths piece = clip(ClipperLib::ctIntersection, section, face);
            pieces.insert(pieces.end(), piece.begin(), piece.end());
        };
        auto planeOf = [&](const std::array<uint32_t, 3>& t) {
            const Vec3 a = mesh.vertices[t[0]];
            const Vec3 n = glm::cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a);
            const double length = glm::length(n);
            return CutPlane{n / length, glm::dot(n / length, a), true, onPlane};
        };
        forFaces(mesh, [&](uint32_t first, uint32_t last) {
            // The face's plane through its largest triangle; its other corners lie within
            // rounding of it, which the plane's onPlane takes in. A face that is not planar
            // to that is taken triangle by triangle (a plane just outside the solid would cut
            // nothing there).
            uint32_t largest = first;
            double largestArea = -1.0;
            for (uint32_t t = first; t < last; ++t) {
                const auto& tri = mesh.triangles[t];
                const Vec3 p = mesh.vertices[tri[0]];
                const Vec3 m = glm::cross(mesh.vertices[tri[1]] - p, mesh.vertices[tri[2]] - p);
                if (glm::dot(m, m) > largestArea) largestArea = glm::dot(m, m), largest = t;
            }
            if (!(largestArea > 0.0)) return;
            const CutPlane plane = planeOf(mesh.triangles[largest]);
            bool planar = true;
            for (uint32_t t = first; t < last && planar; ++t)
                for (uint32_t i : mesh.triangles[t])
                    planar = planar &&
                             std::abs(glm::dot(plane.n, mesh.vertices[i]) - plane.c) <= onPlane;
            if (planar) return addPiece(first, last, plane);
            for (uint32_t t = first; t < last; ++t)
                if (Path p = projected(mesh, mesh.triangles[t], flat.grid); !p.empty())
                    addPiece(t, t + 1, planeOf(mesh.triangles[t]));
        });
    }
    Paths out;
    ClipperLib::Clipper c;
    c.AddPaths(pieces, ClipperLib::ptSubject, true);
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return out;
}

Paths shadowOf(const Flat& flat, int node) {
    if (node < 0) return {};
    const FlatNode& x = flat.nodes[size_t(node)];
    if (x.op == Op::Leaf) return leafShadow(flat.leaves[size_t(x.leaf)], flat.grid);
    if (x.op == Op::Union) return unite(shadowOf(flat, x.left), shadowOf(flat, x.right));
    if (auto exact = faceShadow(flat, node)) return *exact;
    // Too many faces for the face method: mesh the subtree's solid as a whole.
    const Scene scene = Scene::compile(transformed(x.frame, x.source));
    const Bounds3 box = scene.bounds();
    if (box.empty()) return {};
    TessellateOptions options;
    options.tolerance = tol::kLeafMeshToleranceRel * glm::length(box.hi - box.lo);
    options.simplify = false;
    const TessellateResult meshed = tessellate(scene, options);
    flat.result->exact = false;
    ++flat.result->meshedSubtrees;
    flat.result->meshError =
        std::max({flat.result->meshError, meshed.error.max, meshed.backError.max});
    WorldMesh mesh;
    mesh.vertices = meshed.mesh.positions;
    mesh.triangles = meshed.mesh.triangles;
    return leafShadow(mesh, flat.grid);
}

Outline outlineOf(const Paths& paths, const Grid& grid) {
    Outline outline;
    outline.rule = FillRule::EvenOdd;
    for (const Path& path : paths) {
        if (path.size() < 3) continue;
        for (size_t i = 0; i < path.size(); ++i)
            outline.segments.push_back(
                Segment2::line(grid.from(path[i]), grid.from(path[(i + 1) % path.size()])));
    }
    return outline;
}

}  // namespace

ProjectionResult sectionAtZ0(const NodePtr& root) {
    ProjectionResult result;
    const Flat flat = flattenTree(root, Mat4(1.0), result);
    const Paths paths =
        sectionOf(flat, flat.root, CutPlane{Vec3(0, 0, 1), 0.0, true, 0.0, true}, nullptr);
    result.outline = outlineOf(paths, flat.grid);
    return result;
}

ProjectionResult shadowAlongZ(const NodePtr& root) {
    ProjectionResult result;
    const Flat flat = flattenTree(root, Mat4(1.0), result);
    result.outline = outlineOf(shadowOf(flat, flat.root), flat.grid);
    return result;
}

namespace {

bool hasCut(const Node* node) {
    if (!node) return false;
    if (node->op == Op::Intersection || node->op == Op::Difference) return true;
    return hasCut(node->left.get()) || hasCut(node->right.get());
}

// Bounds of a union-only tree from its leaves: vertices for the polyhedral ones, the
// primitive's tight bounds under the map for the rest.
void unionBounds(const Node* node, const Mat4& parent, Bounds3& out) {
    if (!node) return;
    const Mat4 here = parent * node->parentFromNode;
    if (node->op != Op::Leaf) {
        unionBounds(node->left.get(), here, out);
        unionBounds(node->right.get(), here, out);
        return;
    }
    if (isPolyhedral(node->primitive)) {
        out.extend(leafMesh(node->primitive, here, 0.0).box);
        return;
    }
    out.extend(std::visit(
        [&](const auto& shape) {
            if constexpr (HasTightBounds<std::decay_t<decltype(shape)>>)
                return shape.boundsUnder(here);
            else
                return transformBounds(here, shape.bounds());
        },
        node->primitive));
}

Bounds3 pathBounds(const Paths& paths, const Grid& grid) {
    Bounds3 b;
    for (const Path& path : paths)
        for (const IntPoint& p : path) b.extend(Vec3(grid.from(p), 0.0));
    return b;
}

// A subtree's shadow by axialShadow, and the z interval all its leaves span when they span one
// (empty for the empty solid; `oneInterval` false when they do not, or one is sheared).
struct Axial {
    NodePtr shape;
    bool oneInterval = true;
    double lo = kInfinity, hi = -kInfinity;
};

// Whether two subtrees' solids are their regions times one interval (an empty one takes any).
bool shareInterval(const Axial& a, const Axial& b) {
    if (!a.oneInterval || !b.oneInterval) return false;
    return !a.shape || !b.shape || (a.lo == b.lo && a.hi == b.hi);
}

std::optional<Axial> axial(const Node* node, const Mat4& parent, Tags tags) {
    if (!node) return Axial{};
    const Mat4 here = parent * node->parentFromNode;
    if (node->op == Op::Leaf) {
        const auto* e = std::get_if<Extrusion>(&node->primitive);
        if (!e || e->kind != Extrusion::Kind::Linear || e->twist != 0.0 || e->scale != Vec2(1.0) ||
            here[2].x != 0.0 || here[2].y != 0.0)
            return std::nullopt;
        // The map to x, y: (x, y, z) -> A (x, y) + shift whatever z is.
        const glm::dmat2 a(here[0].x, here[0].y, here[1].x, here[1].y);
        if (!(std::abs(glm::determinant(a)) > 0.0)) return std::nullopt;  // no area: meshed
        const Vec2 shift(here[3].x, here[3].y);
        std::shared_ptr<const Outline> outline = e->outline;
        if (a != glm::dmat2(1.0) || shift != Vec2(0.0))
            outline = std::make_shared<Outline>(outline->mapped(a, shift));
        Extrusion shadow = Extrusion::plane(std::move(outline), "projection");
        shadow.accuracy = e->accuracy;
        Axial out;
        out.shape = leaf(shadow, tags);
        out.oneInterval = here[0].z == 0.0 && here[1].z == 0.0;
        const double z0 = here[2].z * e->z0 + here[3].z, z1 = here[2].z * e->z1 + here[3].z;
        out.lo = std::min(z0, z1), out.hi = std::max(z0, z1);
        return out;
    }
    std::optional<Axial> l = axial(node->left.get(), here, tags);
    if (!l) return std::nullopt;
    std::optional<Axial> r = axial(node->right.get(), here, tags);
    if (!r) return std::nullopt;
    if (node->op == Op::Intersection && (!l->shape || !r->shape)) return Axial{};
    if (node->op == Op::Difference && (!l->shape || !r->shape)) return l;
    Axial out;
    out.oneInterval = shareInterval(*l, *r);
    out.lo = l->shape ? l->lo : r->lo, out.hi = l->shape ? l->hi : r->hi;
    switch (node->op) {
        case Op::Union:
            out.shape = unite(l->shape, r->shape, tags);
            return out;
        case Op::Intersection:
            if (!out.oneInterval) return std::nullopt;
            out.shape = intersect(l->shape, r->shape, tags);
            return out;
        default:
            if (!out.oneInterval) return std::nullopt;
            out.shape = subtract(l->shape, r->shape, tags);
            return out;
    }
}

}  // namespace

std::optional<NodePtr> axialShadow(const NodePtr& root, Tags tags) {
    std::optional<Axial> out = axial(root.get(), Mat4(1.0), tags);
    if (!out) return std::nullopt;
    return out->shape;
}

Bounds3 solidBounds(const NodePtr& root) {
    Bounds3 out;
    if (!hasCut(root.get())) {
        unionBounds(root.get(), Mat4(1.0), out);
        return out;
    }
    ProjectionResult ignored;
    const Flat alongZ = flattenTree(root, Mat4(1.0), ignored);
    const Bounds3 xy = pathBounds(shadowOf(alongZ, alongZ.root), alongZ.grid);
    if (xy.empty()) return out;
    // Along x: the frame (x, y, z) -> (y, z, x) puts z on the grid's second axis.
    Mat4 permute(0.0);
    permute[0] = Vec4(0, 0, 1, 0);  // x -> third
    permute[1] = Vec4(1, 0, 0, 0);  // y -> first
    permute[2] = Vec4(0, 1, 0, 0);  // z -> second
    permute[3] = Vec4(0, 0, 0, 1);
    const Flat alongX = flattenTree(root, permute, ignored);
    const Bounds3 yz = pathBounds(shadowOf(alongX, alongX.root), alongX.grid);
    out.lo = Vec3(xy.lo.x, xy.lo.y, yz.lo.y);
    out.hi = Vec3(xy.hi.x, xy.hi.y, yz.hi.y);
    return out;
}

}  // namespace csg
