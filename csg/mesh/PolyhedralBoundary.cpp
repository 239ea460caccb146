#include "csg/mesh/PolyhedralBoundary.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <unordered_map>
#include <variant>
#include <vector>

#include "csg/mesh/BoxGrid.h"
#include "csg/mesh/BoxIndex.h"
#include "csg/mesh/CoplanarMerge.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/Simplify.h"
#include "csg/mesh/TouchingSheets.h"
#include "primitives/Box.h"
#include "primitives/ConvexPolytope.h"
#include "primitives/Polyhedron.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

using Polygon = std::vector<Vec3>;

// A face of a leaf, in world coordinates: a convex polygon in the plane n . p = c.
struct Face {
    Polygon corners;
    Vec3 n;
    double c = 0.0;
    Bounds3 box;        // where it may bound the part: its corners' box within its leaf's reach
    Bounds3 cornerBox;  // its corners' box
    uint32_t leaf = 0;
    uint16_t id = 0;  // the face its leaf's span ends name (a mesh's: Polyhedron::faceOf)
};

Vec3 newellNormal(const Polygon& p) {
    Vec3 n(0.0);
    for (size_t i = 0, k = p.size(); i < k; ++i) {
        const Vec3& a = p[i];
        const Vec3& b = p[(i + 1) % k];
        n += Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

Vec3 centroidOf(const Polygon& p) {
    Vec3 s(0.0);
    for (const Vec3& v : p) s += v;
    return s / double(p.size());
}

// Adds the face with corners (in local coordinates) under m; faces without area are left out
// (no line can end a span on them).
void addFace(const Mat4& m, const Polygon& local, uint32_t leaf, uint16_t id,
             std::vector<Face>& out) {
    Face f;
    f.corners.reserve(local.size());
    for (const Vec3& p : local) f.corners.push_back(Vec3(m * glm::dvec4(p, 1.0)));
    const Vec3 n = newellNormal(f.corners);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) return;
    f.n = n / length;
    f.c = glm::dot(f.n, centroidOf(f.corners));
    for (const Vec3& p : f.corners) f.cornerBox.extend(p);
    f.box = f.cornerBox;
    f.leaf = leaf, f.id = id;
    out.push_back(std::move(f));
}

// The faces of one leaf, with the face ids its spans report; false when it is not a polyhedron
// this method takes.
bool leafFaces(const Scene& scene, uint32_t leaf, std::vector<Face>& out) {
    const Primitive& p = scene.leafPrimitive(leaf);
    if (!polyhedralLeaf(p)) return false;
    const Mat4& m = scene.leafWorldFromLocal(leaf);
    if (const auto* box = std::get_if<Box>(&p)) {
        // Face 2a is the low side of axis a, 2a + 1 the high side (Box.h).
        for (int a = 0; a < 3; ++a)
            for (int side = 0; side < 2; ++side) {
                const int b = (a + 1) % 3, c = (a + 2) % 3;
                Polygon q(4);
                for (int k = 0; k < 4; ++k) {
                    Vec3 v;
                    v[a] = side ? box->hi[a] : box->lo[a];
                    v[b] = (k == 1 || k == 2) ? box->hi[b] : box->lo[b];
                    v[c] = (k >= 2) ? box->hi[c] : box->lo[c];
                    q[size_t(k)] = v;
                }
                addFace(m, q, leaf, uint16_t(2 * a + side), out);
            }
        return true;
    }
    if (const auto* poly = std::get_if<ConvexPolytope>(&p)) {
        const ConvexPolytopeData& d = *poly->data;
        // Face f is plane f (ConvexPolytope.h).
        for (size_t f = 0; f + 1 < d.faceStarts.size(); ++f) {
            Polygon q;
            for (uint32_t k = d.faceStarts[f]; k < d.faceStarts[f + 1]; ++k)
                q.push_back(d.vertices[d.faceVertices[k]]);
            addFace(m, q, leaf, uint16_t(f), out);
        }
        return true;
    }
    if (const auto* mesh = std::get_if<Polyhedron>(&p)) {
        const PolyhedronData& d = *mesh->data;
        for (size_t t = 0; t < d.triangles.size(); ++t) {
            const auto& tri = d.triangles[t];
            addFace(m, {d.vertices[tri[0]], d.vertices[tri[1]], d.vertices[tri[2]]}, leaf,
                    Polyhedron::faceOf(uint32_t(t)), out);
        }
        return true;
    }
    return false;
}

// A cut: the segment of the plane m . p = o (perpendicular to the face it cuts) whose points
// have u . p in [uLo, uHi], u the direction of the segment.
struct Cut {
    Vec3 m;
    double o;
    Vec3 u;
    double uLo, uHi;
};

// Which side of the plane m . p = o the polygon lies on, points within eps of it being on both:
// -1 wholly below (or on), +1 wholly above (or on), 0 across it, when lo and hi get its two
// halves (each with the points on the plane).
int splitPolygon(const Polygon& piece, const Vec3& m, double o, double eps, Polygon& lo,
                 Polygon& hi) {
    bool below = false, above = false;
    for (const Vec3& v : piece) {
        const double s = glm::dot(m, v) - o;
        below = below || s < -eps;
        above = above || s > eps;
    }
    if (!above) return -1;
    if (!below) return 1;
    lo.clear(), hi.clear();
    for (size_t i = 0, k = piece.size(); i < k; ++i) {
        const Vec3& a = piece[i];
        const Vec3& b = piece[(i + 1) % k];
        const double sa = glm::dot(m, a) - o, sb = glm::dot(m, b) - o;
        if (sa <= eps) lo.push_back(a);
        if (sa >= -eps) hi.push_back(a);
        if ((sa < -eps && sb > eps) || (sa > eps && sb < -eps)) {
            const Vec3 x = a + (b - a) * (sa / (sa - sb));
            lo.push_back(x);
            hi.push_back(x);
        }
    }
    return 0;
}

// A piece's axis box, as its middle and half extents.
struct PieceBox {
    Vec3 middle, half;
};

PieceBox pieceBox(const Polygon& piece) {
    Vec3 lo(kInfinity), hi(-kInfinity);
    for (const Vec3& v : piece) lo = glm::min(lo, v), hi = glm::max(hi, v);
    return {0.5 * (lo + hi), 0.5 * (hi - lo)};
}

// Whether a . v - o, for every corner v of a piece in the box, surely lies below `below` or
// surely above `above`, as the corners' own products would give it: the bound's rounding and
// theirs are within gamma(8) of the products' magnitude (the box's middle and half extents
// each round once).
bool surelyOutside(const PieceBox& box, const Vec3& a, double o, double below, double above) {
    const Vec3 size = glm::abs(a);
    const double centre = glm::dot(a, box.middle) - o, reach = glm::dot(size, box.half);
    const double rounding =
        tol::gamma(8) * (glm::dot(size, glm::abs(box.middle) + box.half) + std::abs(o));
    return centre + reach + rounding < below || centre - reach - rounding > above;
}

// Whether the piece's box surely lies off the cut's segment or wholly on one side of its plane
// (within eps of it counting as either side): then the cut does not split the piece.
bool cutMisses(const PieceBox& box, const Cut& cut, double eps) {
    return surelyOutside(box, cut.u, 0.0, cut.uLo - eps, cut.uHi + eps) ||
           surelyOutside(box, cut.m, cut.o, eps, -eps);
}

// Whether the cut's segment reaches the piece and its plane splits it (into lo and hi). A piece
// the segment does not reach stays whole: the cut is no border there (the T-junctions this
// leaves within a face are closed later like any other).
bool cutSplits(const Polygon& piece, const PieceBox& box, const Cut& cut, double eps, Polygon& lo,
               Polygon& hi) {
    if (cutMisses(box, cut, eps)) return false;
    double uMin = kInfinity, uMax = -kInfinity;
    for (const Vec3& v : piece) {
        const double along = glm::dot(cut.u, v);
        uMin = std::min(uMin, along), uMax = std::max(uMax, along);
    }
    return !(uMax < cut.uLo - eps || uMin > cut.uHi + eps) &&
           splitPolygon(piece, cut.m, cut.o, eps, lo, hi) == 0;
}

// splitByCuts's scratch, kept from face to face.
struct PieceScratch {
    // A piece yet to be split by the cuts listed at cutIds[begin, end), in the cuts' order.
    struct Pending {
        Polygon piece;
        PieceBox box;
        size_t begin, end;
    };
    std::vector<Pending> todo;
    std::vector<uint32_t> cutIds;
};

// The pieces of the face cut by every cut in turn, each piece split into lo and hi in its place
// in the list. Done piece by piece, depth first: a piece goes on to the cuts after the one that
// made it, and takes along only those its box may meet, each tried by the box first. A face
// under the edges of thousands of coplanar triangles (an imported mesh's finely divided face on
// a cube's) had every cut tried on every piece made so far, corners and all: a cube in the
// corner of a polyhedron cube of 172 800 triangles took 28.4 s to cut, 9.8 s so (the lists
// stay long where pieces are long slivers).
void splitByCuts(const Polygon& face, const std::vector<Cut>& cuts, double eps, PieceScratch& work,
                 std::vector<Polygon>& pieces) {
    pieces.clear();
    work.todo.clear();
    work.cutIds.resize(cuts.size());
    for (uint32_t i = 0; i < cuts.size(); ++i) work.cutIds[i] = i;
    work.todo.push_back({face, pieceBox(face), 0, cuts.size()});
    Polygon lo, hi;
    while (!work.todo.empty()) {
        PieceScratch::Pending p = std::move(work.todo.back());
        work.todo.pop_back();
        work.cutIds.resize(p.end);  // the lists past it were those of pieces already done
        size_t k = p.begin;
        while (k < p.end && !cutSplits(p.piece, p.box, cuts[work.cutIds[k]], eps, lo, hi)) ++k;
        if (k == p.end) {
            pieces.push_back(std::move(p.piece));
            continue;
        }
        // hi below lo on the stack: lo's pieces come first, as they take its place.
        for (Polygon* part : {&hi, &lo}) {
            if (part->size() < 3) continue;
            const PieceBox box = pieceBox(*part);
            const size_t begin = work.cutIds.size();
            for (size_t j = k + 1; j < p.end; ++j)
                if (!cutMisses(box, cuts[work.cutIds[j]], eps))
                    work.cutIds.push_back(work.cutIds[j]);
            work.todo.push_back({*part, box, begin, work.cutIds.size()});
        }
    }
}

// A half-space m . p <= o (m unit): a convex leaf's face, or its section by a face's plane (m
// then in that plane).
struct HalfPlane {
    Vec3 m;
    double o;
};

// A convex leaf (a box or a polytope) cuts the face f where its section by f's plane, a convex
// polygon (the half-planes its face planes leave there), meets f: each piece that polygon's
// interior meets is split into the part inside it and one part outside each of its edges, and
// nothing else is cut. (Cut by the lines of the section's edges one by one, the parts outside
// would be cut again by every later line: OpenSCAD's 64 x 32 sphere across a cube's face makes
// ~64 pieces this way, thousands by lines.) planes: the leaf's faces, as world planes n . p = c.
void cutByConvexLeaf(std::vector<Polygon>& pieces, const Face& f,
                     const std::vector<HalfPlane>& planes, double eps,
                     std::vector<HalfPlane>& section, std::vector<Polygon>& scratch) {
    section.clear();
    // The ball around f's corners decides most planes with one product: a plane that passes
    // farther from its centre than its radius has f wholly on one side.
    const Vec3 middle = centroidOf(f.corners);
    double radius = 0.0;
    for (const Vec3& v : f.corners) radius = std::max(radius, glm::distance(v, middle));
    radius += eps;
    for (const HalfPlane& g : planes) {
        const double gap = glm::dot(g.m, middle) - g.o;
        if (gap < -radius) continue;  // f lies inside this face's half-space
        if (gap > radius) return;     // f lies outside it: the leaf misses f
        const double cosine = glm::dot(f.n, g.m);
        if (std::abs(cosine) > 1.0 - tol::kPolyBoundaryParallelCos) {
            // Parallel: f's plane is outside this face's half-space (the leaf misses it), or
            // inside or on it (no border in the plane).
            if (glm::dot(g.m, f.corners[0]) - g.o > eps) return;
            continue;
        }
        const Vec3 m = g.m - cosine * f.n;
        const double length = glm::length(m);
        const HalfPlane h{m / length, (g.o - cosine * f.c) / length};
        double lo = kInfinity, hi = -kInfinity;
        for (const Vec3& v : f.corners) {
            const double s = glm::dot(h.m, v) - h.o;
            lo = std::min(lo, s), hi = std::max(hi, s);
        }
        if (lo >= -eps) return;   // f lies outside the section, or only touches it
        if (hi <= eps) continue;  // f lies inside this half-plane
        section.push_back(h);
    }
    if (section.empty()) return;  // f lies inside the section
    // Only the half-planes that give an edge of the section within f cut: clipping f by every
    // one in turn, those that take something off. (Many of a sphere's ~2 000 planes cross f
    // outside the section; cutting by them would only split the parts outside it again.)
    Polygon within = f.corners, lo, hi;
    size_t kept = 0;
    for (const HalfPlane& h : section) {
        const int side = splitPolygon(within, h.m, h.o, eps, lo, hi);
        if (side > 0 || (side == 0 && lo.size() < 3)) return;  // the section misses f
        if (side == 0) within.swap(lo), section[kept++] = h;
    }
    section.resize(kept);
    // A half-plane that took something off early may bound nothing once later ones have cut.
    std::erase_if(section, [&](const HalfPlane& h) {
        for (const Vec3& v : within)
            if (std::abs(glm::dot(h.m, v) - h.o) <= eps) return false;
        return true;
    });
    scratch.clear();
    Polygon rest;
    for (Polygon& piece : pieces) {
        // Whether the section's interior meets the piece: what is left inside every half-plane.
        rest = piece;
        bool meets = true;
        for (const HalfPlane& h : section) {
            const int side = splitPolygon(rest, h.m, h.o, eps, lo, hi);
            if (side > 0 || (side == 0 && lo.size() < 3)) {
                meets = false;
                break;
            }
            if (side == 0) rest.swap(lo);
        }
        if (!meets) {
            scratch.push_back(std::move(piece));
            continue;
        }
        for (const HalfPlane& h : section)
            if (splitPolygon(piece, h.m, h.o, eps, lo, hi) == 0) {
                if (hi.size() >= 3) scratch.push_back(hi);
                piece.swap(lo);
            }
        scratch.push_back(std::move(piece));
    }
    pieces.swap(scratch);
}

// The cuts the face g makes on the face f (see the header's step 1).
void cutsOf(const Face& f, const Face& g, double eps, std::vector<Cut>& out) {
    const double cosine = glm::dot(f.n, g.n);
    if (std::abs(cosine) > 1.0 - tol::kPolyBoundaryParallelCos) {
        // Parallel: a coplanar face cuts along its edges' lines, any other not at all.
        if (std::abs(glm::dot(f.n, g.corners[0]) - f.c) > eps) return;
        for (size_t i = 0, k = g.corners.size(); i < k; ++i) {
            const Vec3& a = g.corners[i];
            const Vec3 e = g.corners[(i + 1) % k] - a;
            const Vec3 m = glm::cross(f.n, e);
            const double length = glm::length(m), edge = glm::length(e);
            if (!(length > 0.0 && edge > 0.0)) continue;
            const Vec3 u = e / edge;
            out.push_back(
                {m / length, glm::dot(m / length, a), u, glm::dot(u, a), glm::dot(u, a) + edge});
        }
        return;
    }
    // f must reach g's plane (else the line of g in f's plane misses f) ...
    bool fBelow = false, fAbove = false;
    for (const Vec3& v : f.corners) {
        const double s = glm::dot(g.n, v) - g.c;
        fBelow = fBelow || s < -eps;
        fAbove = fAbove || s > eps;
    }
    if (!(fBelow && fAbove)) {
        bool fOn = false;
        for (const Vec3& v : f.corners) fOn = fOn || std::abs(glm::dot(g.n, v) - g.c) <= eps;
        if (!fOn) return;
    }
    // ... and g must meet f's plane in more than a point.
    Vec3 lo(0.0), hi(0.0);
    int found = 0;
    const Vec3 u = glm::normalize(glm::cross(f.n, g.n));
    double uLo = kInfinity, uHi = -kInfinity;
    const auto take = [&](const Vec3& p) {
        const double s = glm::dot(u, p);
        if (s < uLo) uLo = s, lo = p;
        if (s > uHi) uHi = s, hi = p;
        ++found;
    };
    for (size_t i = 0, k = g.corners.size(); i < k; ++i) {
        const Vec3& a = g.corners[i];
        const Vec3& b = g.corners[(i + 1) % k];
        const double sa = glm::dot(f.n, a) - f.c, sb = glm::dot(f.n, b) - f.c;
        if (std::abs(sa) <= eps) take(a);
        if ((sa < -eps && sb > eps) || (sa > eps && sb < -eps))
            take(a + (b - a) * (sa / (sa - sb)));
    }
    if (found < 2 || !(uHi - uLo > eps)) return;
    // The cut's plane holds the line and f's normal.
    const Vec3 m = glm::normalize(glm::cross(u, f.n));
    out.push_back({m, 0.5 * (glm::dot(m, lo) + glm::dot(m, hi)), u, uLo, uHi});
}

// A kept piece: its corners wound counter-clockwise seen from outside the part.
struct Piece {
    Polygon corners;
    uint32_t material = 0;
};

// One worker's scratch for boundaryPieces, kept from face to face.
struct CutScratch {
    std::vector<uint32_t> near, convexLeaves, coincident, covering;
    std::vector<Cut> cuts;
    std::vector<HalfPlane> section;
    std::vector<Polygon> pieces, split;
    PieceScratch cutting;
};

// Whether g lies in f's plane (either way round).
bool inPlaneOf(const Face& f, const Face& g, double eps) {
    const double cosine = glm::dot(f.n, g.n);
    if (std::abs(cosine) <= 1.0 - tol::kPolyBoundaryParallelCos) return false;
    for (const Vec3& v : g.corners)
        if (std::abs(glm::dot(f.n, v) - f.c) > eps) return false;
    return true;
}

// Whether p (in g's plane) lies inside g's convex polygon, by more than eps: on one side of
// every edge (whichever way the corners run around g.n). A piece is tested against every
// coincident face near it, and most lie wholly off it: the corners' box decides those (p's foot on
// g's plane lies in it, and p is as far from its foot as from the plane), and the first edge that
// disagrees most others.
bool insideFace(const Face& g, const Vec3& p, double eps) {
    const double reach = std::abs(glm::dot(g.n, p) - g.c) + eps;
    if (glm::any(glm::lessThan(p, g.cornerBox.lo - reach)) ||
        glm::any(glm::greaterThan(p, g.cornerBox.hi + reach)))
        return false;
    int left = 0, right = 0;
    for (size_t i = 0, k = g.corners.size(); i < k; ++i) {
        const Vec3& a = g.corners[i];
        const Vec3& b = g.corners[(i + 1) % k];
        const Vec3 edge = b - a;
        const double side = glm::dot(glm::cross(edge, p - a), g.n);
        const double margin = eps * glm::length(edge);
        left += side > margin;
        right += side < -margin;
        if (left <= int(i) && right <= int(i)) return false;
    }
    return true;
}

// Step 1 and 2 for one face.
// convexPlanes: per leaf, its face planes when it is convex (a box or a polytope), else none.
void boundaryPieces(const Scene& scene, const std::vector<Face>& faces, const BoxIndex& index,
                    const std::vector<std::vector<HalfPlane>>& convexPlanes, uint32_t face,
                    double eps, QueryContext& ctx, CutScratch& work, std::vector<Piece>& out,
                    uint64_t& piecesMade) {
    const Face& f = faces[face];
    work.near.clear();
    Bounds3 box = f.box;
    box.lo -= Vec3(eps), box.hi += Vec3(eps);
    index.forEachOverlapping(box, [&](uint32_t g) {
        if (g != face && faces[g].leaf != f.leaf) work.near.push_back(g);
    });
    // In face order, so the cuts (and so the pieces) do not depend on the index's order.
    std::sort(work.near.begin(), work.near.end());
    std::vector<Cut>& cuts = work.cuts;
    cuts.clear();
    work.convexLeaves.clear();
    for (const uint32_t g : work.near) {
        if (convexPlanes[faces[g].leaf].empty())
            cutsOf(f, faces[g], eps, cuts);
        else
            work.convexLeaves.push_back(faces[g].leaf);
    }
    // Faces of other leaves in f's plane: where one covers a piece, the piece and its piece
    // are one surface, which the part keeps once, as the lower leaf's (below).
    work.coincident.clear();
    for (const uint32_t g : work.near)
        if (inPlaneOf(f, faces[g], eps)) work.coincident.push_back(g);
    std::sort(work.convexLeaves.begin(), work.convexLeaves.end());
    work.convexLeaves.erase(std::unique(work.convexLeaves.begin(), work.convexLeaves.end()),
                            work.convexLeaves.end());
    std::vector<Polygon>& pieces = work.pieces;
    splitByCuts(f.corners, cuts, eps, work.cutting, pieces);
    for (const uint32_t leaf : work.convexLeaves)
        cutByConvexLeaf(pieces, f, convexPlanes[leaf], eps, work.section, work.split);
    piecesMade += pieces.size();
    for (Polygon& piece : pieces) {
        if (glm::length(newellNormal(piece)) <= eps * eps) continue;
        const Vec3 middle = centroidOf(piece);
        // Outside its leaf's reach a face bounds nothing, even where a coincident face of a
        // leaf that reaches there does: the piece is that face's to keep. (The piece was cut
        // only by the faces near f's reach, so its edges need not follow the part there: in
        // Debian's example007 the floor of the first slot's second prism ran on under the
        // second slot's floor and across the post's wall, which its reach does not come near.)
        if (!f.box.contains(middle)) continue;
        // Coincident faces of several leaves cover this piece alike: the merge names one of
        // them at the span end, the lower leaf when their t are equal, else the one it meets
        // first by a rounding that changes from line to line. So a span end on any of them
        // counts, and the piece is kept by the lowest leaf among those facing its way that
        // reach it.
        work.covering.clear();
        bool lowest = true;
        for (const uint32_t g : work.coincident)
            if (glm::dot(faces[g].n, f.n) > 0.0 && faces[g].box.contains(middle) &&
                insideFace(faces[g], middle, eps)) {
                work.covering.push_back(g);
                lowest = lowest && faces[g].leaf > f.leaf;
            }
        if (!lowest) continue;
        // Only the span ends near t = 0 matter: a short stretch of the line lets the bounds
        // skip every leaf it does not come near (the merge is exact on any stretch).
        const double reach = tol::kPolyBoundaryClassifyReach * eps;
        const std::span<const Span> spans = scene.spans(Ray{middle, f.n, -reach, reach}, ctx);
        // The crossing of the face's own plane is at t = 0; a span end there on this very face
        // is the boundary. Entering along n means the part lies ahead: the outside is behind.
        // A mesh of more than Polyhedron::kFaceIds triangles names a residue, shared by a
        // triangle in every kFaceIds: one of those others met within eps of this face's
        // middle is the leaf's surface there too (a neighbour at an edge the middle is near:
        // the same facing), unless the mesh passes within eps of itself, where a piece kept
        // or dropped wrongly leaves the pieces open or doubled, which is declined below.
        const auto onFace = [&](const Hit& h) {
            if (std::abs(h.t) > eps) return false;
            if (h.leaf == f.leaf && h.face == f.id) return true;
            for (const uint32_t g : work.covering)
                if (faces[g].leaf == h.leaf && faces[g].id == h.face) return true;
            return false;
        };
        int facing = 0;
        for (const Span& s : spans) {
            if (onFace(s.in)) facing = -1;
            if (onFace(s.out)) facing = 1;
        }
        if (facing == 0) continue;
        if (facing < 0) std::reverse(piece.begin(), piece.end());
        out.push_back({std::move(piece), scene.leafTags(f.leaf).material});
    }
}

// Welds positions closer than eps into one index: a hash of cells of edge 2 eps, where a point's
// neighbours within eps lie in its own cell or, along each axis, in the one cell on the side of
// the nearer border (8 cells, not 27).
class Welder {
public:
    explicit Welder(double eps) : eps_(eps), cell_(2.0 * eps) {}

    uint32_t index(const Vec3& p) {
        int64_t c[3], step[3];
        for (int a = 0; a < 3; ++a) {
            const double x = p[a] / cell_, floor = std::floor(x);
            c[a] = int64_t(floor);
            step[a] = x - floor < 0.5 ? -1 : 1;
        }
        for (int k = 0; k < 8; ++k) {
            const auto it =
                cells_.find(key(c[0] + (k & 1 ? step[0] : 0), c[1] + (k & 2 ? step[1] : 0),
                                c[2] + (k & 4 ? step[2] : 0)));
            if (it == cells_.end()) continue;
            for (const uint32_t i : it->second)
                if (glm::distance(positions[i], p) <= eps_) return i;
        }
        const uint32_t i = uint32_t(positions.size());
        positions.push_back(p);
        cells_[key(c[0], c[1], c[2])].push_back(i);
        return i;
    }

    std::vector<Vec3> positions;

private:
    static uint64_t key(int64_t x, int64_t y, int64_t z) {
        return (uint64_t(x) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(y) * 0xC2B2AE3D27D4EB4Full) ^
               (uint64_t(z) * 0x165667B19E3779F9ull);
    }
    double eps_, cell_;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

// Inserts into every edge the welded vertices that lie on it (within eps of the segment,
// strictly between its ends), in order along it. Only edges no other piece runs the other way
// can hold such a vertex, and only the ends of such edges can be one: those "loose" vertices are
// listed in a grid of cells about as large as the loose edges are long, so an edge looks only
// at the loose vertices near it. Polygons are independent, so they are done on every worker.
uint64_t closeTJunctions(const std::vector<Vec3>& positions,
                         std::vector<std::vector<uint32_t>>& polygons, double eps, int threads) {
    const auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
    std::vector<uint64_t> directed;
    for (const auto& poly : polygons)
        for (size_t i = 0, k = poly.size(); i < k; ++i)
            directed.push_back(key(poly[i], poly[(i + 1) % k]));
    std::sort(directed.begin(), directed.end());
    const auto paired = [&](uint32_t a, uint32_t b) {
        return std::binary_search(directed.begin(), directed.end(), key(b, a));
    };
    std::vector<uint32_t> loose;
    double looseLength = 0.0;
    for (const auto& poly : polygons)
        for (size_t i = 0, k = poly.size(); i < k; ++i) {
            const uint32_t a = poly[i], b = poly[(i + 1) % k];
            if (paired(a, b)) continue;
            loose.push_back(a), loose.push_back(b);
            looseLength += glm::distance(positions[a], positions[b]);
        }
    if (loose.empty()) return 0;
    const double cell = std::max(looseLength / double(loose.size()) * 2.0, 4.0 * eps);
    std::sort(loose.begin(), loose.end());
    loose.erase(std::unique(loose.begin(), loose.end()), loose.end());
    BoxGrid grid(positions[loose[0]], cell);
    for (const uint32_t v : loose) grid.insert(v, Bounds3{positions[v], positions[v]});

    std::atomic<uint64_t> inserted{0};
    parallelFor(polygons.size(), threads, [&](int, uint64_t p) {
        auto& poly = polygons[p];
        std::vector<uint32_t> out;
        std::vector<std::pair<double, uint32_t>> on;
        for (size_t i = 0, k = poly.size(); i < k; ++i) {
            const uint32_t a = poly[i], b = poly[(i + 1) % k];
            out.push_back(a);
            if (paired(a, b)) continue;
            const Vec3 pa = positions[a], pb = positions[b], e = pb - pa;
            const double length2 = glm::dot(e, e);
            if (!(length2 > 0.0)) continue;
            Bounds3 box{glm::min(pa, pb) - Vec3(eps), glm::max(pa, pb) + Vec3(eps)};
            on.clear();
            grid.forEachNear(box, [&](const BoxGrid::Entry& entry) {
                const uint32_t v = entry.id;
                if (v == a || v == b) return;
                const Vec3 pv = positions[v];
                const double s = glm::dot(pv - pa, e) / length2;
                if (!(s > 0.0 && s < 1.0)) return;
                if (glm::distance(pa + s * e, pv) <= eps) on.push_back({s, v});
            });
            // A vertex in several cells the box overlaps is met once per cell.
            std::sort(on.begin(), on.end());
            on.erase(std::unique(on.begin(), on.end()), on.end());
            for (const auto& [s, v] : on) out.push_back(v);
            inserted += on.size();
        }
        poly.swap(out);
    });
    return inserted;
}

// Ear clipping of a convex polygon whose corners may include points on its edges (T-junction
// vertices): an ear is cut only where its tip stands more than the weld distance off the line
// through its neighbours, and where what it leaves has that much height too (cutting the last
// corner off a row of edge points would leave them collinear, with no ear at all). Areas are
// doubled and measured along the polygon's normal.
void triangulateConvex(const std::vector<Vec3>& positions, std::vector<uint32_t> poly,
                       const Vec3& normal, double weld, uint32_t material, TriangleMesh& out) {
    const auto area = [&](uint32_t a, uint32_t b, uint32_t c) {
        return glm::dot(glm::cross(positions[b] - positions[a], positions[c] - positions[a]),
                        normal);
    };
    double left = 0.0;
    for (size_t i = 1; i + 1 < poly.size(); ++i) left += area(poly[0], poly[i], poly[i + 1]);
    size_t i = 0, stale = 0;
    while (poly.size() > 3 && stale < poly.size()) {
        const size_t k = poly.size();
        const uint32_t a = poly[(i + k - 1) % k], b = poly[i], c = poly[(i + 1) % k];
        const double ear = area(a, b, c);
        const double base = weld * glm::distance(positions[a], positions[c]);
        if (ear > base && left - ear > base) {
            out.triangles.push_back({a, b, c});
            out.triangleMaterial.push_back(material);
            poly.erase(poly.begin() + long(i));
            left -= ear;
            stale = 0;
        } else {
            ++i, ++stale;
        }
        i %= poly.size();
    }
    if (poly.size() == 3) {
        out.triangles.push_back({poly[0], poly[1], poly[2]});
        out.triangleMaterial.push_back(material);
    }
}

}  // namespace

bool polyhedralLeaf(const Primitive& p) {
    if (std::holds_alternative<Box>(p)) return true;
    if (const auto* poly = std::get_if<ConvexPolytope>(&p)) return poly->data != nullptr;
    const auto* mesh = std::get_if<Polyhedron>(&p);
    return mesh && mesh->data;
}

bool allLeavesPolyhedral(const Scene& scene) {
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf)
        if (!polyhedralLeaf(scene.leafPrimitive(leaf))) return false;
    return true;
}

std::optional<TriangleMesh> polyhedralBoundary(const Scene& scene, int threads,
                                               PolyhedralBoundaryStats* stats,
                                               const ItemDistributor* distribute) {
    PolyhedralBoundaryStats local;
    PolyhedralBoundaryStats& s = stats ? *stats : local;
    s = {};
    auto clock = std::chrono::steady_clock::now();
    const auto lap = [&clock]() {
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - clock).count();
        clock = now;
        return seconds;
    };
    const Bounds3 bounds = scene.bounds();
    if (bounds.empty() || !bounds.finite()) {
        s.declined = "the part is empty or unbounded";
        return std::nullopt;
    }
    std::vector<Face> all;
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf)
        if (!leafFaces(scene, leaf, all)) {
            s.declined = "a leaf is not a polyhedron";
            return std::nullopt;
        }
    s.faces = all.size();
    // The face planes of every convex leaf, from all its faces (those past its reach too: the
    // leaf's section of a face's plane needs every one).
    // A face's Newell normal follows its corners' order, which need not face out (a box's low
    // and high sides run the same way): each plane is turned to have the leaf's centre of
    // corners, an interior point, on its inner side.
    std::vector<std::vector<HalfPlane>> convexPlanes(scene.leafCount());
    std::vector<Vec3> centre(scene.leafCount(), Vec3(0.0));
    std::vector<double> corners(scene.leafCount(), 0.0);
    for (const Face& f : all)
        for (const Vec3& v : f.corners) centre[f.leaf] += v, corners[f.leaf] += 1.0;
    for (const Face& f : all) {
        const Primitive& p = scene.leafPrimitive(f.leaf);
        if (!std::holds_alternative<Box>(p) && !std::holds_alternative<ConvexPolytope>(p)) continue;
        const bool outward = glm::dot(f.n, centre[f.leaf] / corners[f.leaf]) < f.c;
        convexPlanes[f.leaf].push_back(outward ? HalfPlane{f.n, f.c} : HalfPlane{-f.n, -f.c});
    }
    const double size =
        std::max({1.0, glm::length(bounds.extent()), std::abs(bounds.lo.x), std::abs(bounds.lo.y),
                  std::abs(bounds.lo.z), std::abs(bounds.hi.x), std::abs(bounds.hi.y),
                  std::abs(bounds.hi.z)});
    const double onPlane = tol::kPolyBoundaryOnPlaneRel * size;
    const double weld = tol::kPolyBoundaryWeldRel * size;

    // Only the part of a face within its leaf's reach can bound the part (Scene::leafReach):
    // faces outside it are dropped, and the others cut only within it.
    const std::vector<Bounds3> reach = scene.leafReach();
    std::vector<Face> faces;
    for (Face& f : all) {
        Bounds3 within = overlap(f.box, reach[f.leaf]);
        within.lo -= Vec3(onPlane), within.hi += Vec3(onPlane);
        if (within.empty()) continue;
        f.box = within;
        faces.push_back(std::move(f));
    }
    all.clear();

    // Step 1 and 2, face by face on every worker.
    std::vector<Bounds3> nearBoxes(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) {
        nearBoxes[i] = faces[i].box;
        nearBoxes[i].lo -= Vec3(onPlane), nearBoxes[i].hi += Vec3(onPlane);
    }
    const BoxIndex index(std::move(nearBoxes));
    const int workers = workersFor(distribute, threads);
    std::vector<QueryContext> contexts(static_cast<size_t>(workers));
    std::vector<CutScratch> scratch(static_cast<size_t>(workers));
    std::vector<std::vector<Piece>> kept(faces.size());
    std::vector<uint64_t> made(faces.size(), 0);
    const auto cut = [&](int worker, uint64_t i, std::vector<Piece>& pieces, uint64_t& count) {
        boundaryPieces(scene, faces, index, convexPlanes, uint32_t(i), onPlane,
                       contexts[size_t(worker)], scratch[size_t(worker)], pieces, count);
    };
    if (!distribute) {
        parallelFor(faces.size(), workers,
                    [&](int worker, uint64_t i) { cut(worker, i, kept[i], made[i]); });
    } else {
        distribute->run(
            faces.size(), "the faces cut",
            [&](int worker, uint64_t i, std::string& bytes) {
                std::vector<Piece> pieces;
                uint64_t count = 0;
                cut(worker, i, pieces, count);
                ByteWriter out(bytes);
                out.value(count);
                out.value(uint64_t(pieces.size()));
                for (const Piece& piece : pieces) {
                    out.value(piece.material);
                    out.values(piece.corners);
                }
            },
            [&](uint64_t i, std::string_view bytes) {
                ByteReader in(bytes);
                made[i] = in.value<uint64_t>();
                const uint64_t pieces = std::min<uint64_t>(in.value<uint64_t>(), bytes.size());
                for (uint64_t k = 0; k < pieces; ++k) {
                    Piece& piece = kept[i].emplace_back();
                    piece.material = in.value<uint32_t>();
                    piece.corners = in.values<Vec3>();
                }
            });
    }

    s.classifySeconds = lap();

    // Step 3: weld, close T-junctions, triangulate, merge the pieces of a face.
    Welder welder(weld);
    std::vector<std::vector<uint32_t>> polygons;
    std::vector<uint32_t> materials;
    std::vector<Vec3> normals;
    for (size_t i = 0; i < faces.size(); ++i) {
        s.pieces += made[i];
        for (const Piece& piece : kept[i]) {
            std::vector<uint32_t> poly;
            for (const Vec3& p : piece.corners) {
                const uint32_t v = welder.index(p);
                if (poly.empty() || poly.back() != v) poly.push_back(v);
            }
            while (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
            if (poly.size() < 3) continue;
            polygons.push_back(std::move(poly));
            materials.push_back(piece.material);
            normals.push_back(glm::normalize(newellNormal(piece.corners)));
            ++s.kept;
        }
    }
    s.tJunctions = closeTJunctions(welder.positions, polygons, weld, threads);
    for (const auto& poly : polygons) s.trianglesBeforeMerge += poly.size() - 2;
    s.assembleSeconds = lap();

    // Step 4: the pieces of each face merged back and triangulated as one polygon with holes.
    if (std::optional<TriangleMesh> merged =
            mergeCoplanar(welder.positions, polygons, normals, materials, weld)) {
        const bool closed = closedOnceSheetsSeparated(*merged);
        s.mergeSeconds = lap();
        if (closed) {
            s.mergedBy = "faces";
            return merged;
        }
    }
    // Where a face touches itself at a vertex (its outline does not chain into loops), the
    // pieces are triangulated one by one and the simplifier merges them.
    TriangleMesh mesh;
    mesh.positions = welder.positions;
    for (size_t i = 0; i < polygons.size(); ++i)
        triangulateConvex(mesh.positions, polygons[i], normals[i], weld, materials[i], mesh);
    if (!closedOnceSheetsSeparated(mesh)) {
        s.declined = "the pieces do not close into a manifold";
        return std::nullopt;
    }
    TriangleMesh simplified = simplify(mesh, weld, nullptr, threads);
    const bool closed = checkTopology(simplified).closedManifold();
    s.mergeSeconds += lap();
    s.mergedBy = closed ? "the simplifier" : "nothing (the simplifier's result was not closed)";
    if (!closed) return mesh;
    return simplified;
}

}  // namespace csg
