#include "csg/mesh/Decimate.h"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>
#include <OpenMesh/Tools/Utils/HeapT.hh>

#include <algorithm>
#include <cfloat>
#include <optional>
#include <unordered_map>
#include <vector>

#include "csg/mesh/BoxGrid.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/TriangleBvh.h"
#include "primitives/base/Bounds.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

// Double positions: a collapse keeps input vertices bit for bit.
struct SimplifyTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status);
};

// A collapse may leave the kept vertex with at most this many neighbours. The decimation
// re-rates every edge around the kept vertex after each collapse, at a cost that grows with
// the square of its valence, so letting a flat face shrink to one fan of hundreds of
// triangles makes simplification slower than meshing; 24 still lets a flat face coarsen to
// triangles ~24 grid cells across wherever its outline allows.
constexpr unsigned kMaxValence = 24;
// Secondary priority, edge length squared against the quadric's squared distance (unit:
// relative): among equally flat collapses the shortest edge goes first, so a plane coarsens
// evenly instead of growing long slivers from one corner.
constexpr double kLengthPriority = 1e-4;
// The crossing check's grid cells, in mean edge lengths of the piece as given (unit: ratio):
// a new fan's triangles start about one edge across and grow to a few; cells of a few edges
// keep both the cells a query visits and the triangles each cell lists to a few dozen.
constexpr double kGridCellEdges = 4.0;

// The mesh type the decimation runs on. It asks this type whether a collapse keeps the mesh a
// 2-manifold (is_collapse_ok), for every candidate halfedge of every re-rated vertex, then
// asks for a priority. OpenMesh 9.0's TriConnectivity::is_collapse_ok allocates and looks a
// property up by name on each call (on csg_grid3's grid mesh that dominated decimation:
// bench/README.md, where simplification's time went); this one makes the same tests with a mark per
// vertex that a counter clears, and first the cheap bounds that reject most candidates (the quadric
// at the kept vertex, the valence cap), so the link condition and the fan run only for the rest.
// valence and find_halfedge shadow OpenMesh's out-of-line versions. Walks around a vertex step from
// one outgoing halfedge to the next by OpenMesh's inline cw_rotated_halfedge_handle (the next
// halfedge of the opposite one).
class OmMesh : public OpenMesh::TriMesh_ArrayKernelT<SimplifyTraits> {
public:
    OpenMesh::VPropHandleT<Quadric> quadrics;  // the planes merged into each vertex
    double maxSquared = 0.0;                   // the deviation bound, squared

    OmMesh() { add_property(quadrics); }

    // The quadric error of moving everything merged into a and b onto b's position.
    double mergedError(VertexHandle a, VertexHandle b) const {
        Quadric q = property(quadrics, a);
        q += property(quadrics, b);
        return std::max(0.0, q(point(b)));
    }
    // mergedError(v0, v1) of the collapse along v0v1, which is_collapse_ok has just computed:
    // a collapse's priority is asked for only right after is_collapse_ok passed that same
    // halfedge. A collapse changes quadrics only after it is made, which forgets the value; the
    // fallback never runs but keeps the answer right if the call order ever changes.
    double collapseError(HalfedgeHandle v0v1, VertexHandle v0, VertexHandle v1) const {
        return v0v1 == errorOf_ ? error_ : mergedError(v0, v1);
    }
    void forgetCollapseError() { errorOf_ = HalfedgeHandle(); }

    unsigned valence(VertexHandle v) const {
        const HalfedgeHandle first = halfedge_handle(v);
        if (!first.is_valid()) return 0;
        unsigned n = 0;
        HalfedgeHandle h = first;
        do {
            ++n;
            h = cw_rotated_halfedge_handle(h);
        } while (h != first);
        return n;
    }

    HalfedgeHandle find_halfedge(VertexHandle from, VertexHandle to) const {
        const HalfedgeHandle first = halfedge_handle(from);
        if (!first.is_valid()) return HalfedgeHandle();
        HalfedgeHandle h = first;
        do {
            if (to_vertex_handle(h) == to) return h;
            h = cw_rotated_halfedge_handle(h);
        } while (h != first);
        return HalfedgeHandle();
    }

    bool is_collapse_ok(HalfedgeHandle v0v1) {
        if (status(edge_handle(v0v1)).deleted()) return false;
        const HalfedgeHandle v1v0 = opposite_halfedge_handle(v0v1);
        const VertexHandle v0 = to_vertex_handle(v1v0), v1 = to_vertex_handle(v0v1);
        if (status(v0).deleted() || status(v1).deleted()) return false;
        // The bound on the kept vertex's quadric.
        error_ = mergedError(v0, v1);
        errorOf_ = v0v1;
        if (error_ > maxSquared) return false;
        // The edges v1-vl and vl-v0 (and v0-vr, vr-v1) must not both be boundary edges. apex
        // finds the third corner of h's triangle (none on a boundary) and checks its two edges.
        const auto apex = [&](HalfedgeHandle h, VertexHandle& corner) {
            if (is_boundary(h)) return true;
            const HalfedgeHandle h1 = next_halfedge_handle(h), h2 = next_halfedge_handle(h1);
            corner = to_vertex_handle(h1);
            return !(is_boundary(opposite_halfedge_handle(h1)) &&
                     is_boundary(opposite_halfedge_handle(h2)));
        };
        VertexHandle vl, vr;
        if (!apex(v0v1, vl) || !apex(v1v0, vr) || vl == vr) return false;
        // The link condition (the one-rings of v0 and v1 share only vl and vr) and the valence
        // cap (the kept vertex gets v0's and v1's neighbours, less v0, v1 themselves and the
        // two neighbours they share), in one walk around each vertex.
        if (ringMark_.size() < n_vertices()) ringMark_.resize(n_vertices(), 0);
        if (++mark_ == 0) {
            std::fill(ringMark_.begin(), ringMark_.end(), 0u);
            mark_ = 1;
        }
        unsigned valences = 0;
        {
            const HalfedgeHandle first = halfedge_handle(v1);
            HalfedgeHandle h = first;
            do {
                ringMark_[size_t(to_vertex_handle(h).idx())] = mark_;
                ++valences;
                h = cw_rotated_halfedge_handle(h);
            } while (h != first);
        }
        {
            const HalfedgeHandle first = halfedge_handle(v0);
            HalfedgeHandle h = first;
            do {
                const VertexHandle w = to_vertex_handle(h);
                if (ringMark_[size_t(w.idx())] == mark_ && w != vl && w != vr) return false;
                ++valences;
                h = cw_rotated_halfedge_handle(h);
            } while (h != first);
        }
        if (valences > kMaxValence + 4) return false;
        // An edge between two boundary vertices must be a boundary edge.
        return !(is_boundary(v0) && is_boundary(v1) && !is_boundary(v0v1) && !is_boundary(v1v0));
    }

private:
    std::vector<uint32_t> ringMark_;
    uint32_t mark_ = 0;
    HalfedgeHandle errorOf_;  // the halfedge whose mergedError error_ holds
    double error_ = 0.0;
};

using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<OmMesh>;
using VertexHandle = OmMesh::VertexHandle;
using HalfedgeHandle = OmMesh::HalfedgeHandle;
using FaceHandle = OmMesh::FaceHandle;

Vec3 toVec(const OmMesh::Point& p) {
    return {p[0], p[1], p[2]};
}

// The decimation loop: OpenMesh's DecimaterT::decimate with one priority module (the same
// heap, the same order of rating, popping and re-rating, so the same collapses), plus a last
// test of the popped collapse against the mesh as it is then: its new fan must not cross or
// overlap other triangles. That test cannot be part of the rating: a vertex is re-rated only
// when its one-ring changes, while a collapse elsewhere may put a triangle in its fan's way (the
// other side of a thin wall or gap), so only the popped collapse sees the current mesh.
class Collapser {
public:
    Collapser(OmMesh& mesh, const CollapseLimits& limits, DecimateStats& stats)
        : m_(mesh),
          limits_(limits),
          stats_(stats),
          checking_(limits.contactTol > 0.0),
          heap_(HeapInterface{this}) {}

    void run() {
        const size_t nv = m_.n_vertices();
        target_.assign(nv, HalfedgeHandle());
        priority_.assign(nv, -1.0f);
        heapPosition_.assign(nv, -1);
        if (checking_) buildGrid();
        heap_.reserve(nv);
        for (const VertexHandle v : m_.vertices()) {
            heap_.reset_heap_position(v);
            if (!m_.status(v).deleted()) rate(v);
        }
        std::vector<VertexHandle> support;
        while (!heap_.empty()) {
            const VertexHandle vp = heap_.front();
            const HalfedgeHandle v0v1 = target_[size_t(vp.idx())];
            heap_.pop_front();
            const CollapseInfo ci(m_, v0v1);
            if (!legal(ci)) continue;
            if (!keepsClear(ci)) {
                // Not this one: the vertex's next best target, if any.
                refused_[uint32_t(v0v1.idx())] = pairOf(ci.v0, ci.v1);
                rate(vp);
                continue;
            }
            support.clear();
            for (auto vv = m_.vv_iter(ci.v0); vv.is_valid(); ++vv) support.push_back(*vv);
            if (checking_) unlistFan(ci.v0);
            m_.collapse(v0v1);
            ++stats_.collapses;
            m_.property(m_.quadrics, ci.v1) += m_.property(m_.quadrics, ci.v0);
            m_.forgetCollapseError();
            if (checking_) relistFan();
            for (const VertexHandle v : support) rate(v);
        }
    }

private:
    // OpenMesh's heap, ordered by priority_, positions in heapPosition_.
    struct HeapInterface {
        Collapser* c;
        bool less(VertexHandle a, VertexHandle b) const {
            return c->priority_[size_t(a.idx())] < c->priority_[size_t(b.idx())];
        }
        bool greater(VertexHandle a, VertexHandle b) const {
            return c->priority_[size_t(a.idx())] > c->priority_[size_t(b.idx())];
        }
        int get_heap_position(VertexHandle v) const { return c->heapPosition_[size_t(v.idx())]; }
        void set_heap_position(VertexHandle v, int at) { c->heapPosition_[size_t(v.idx())] = at; }
    };
    // A triangle a collapse would make: as the contact test takes it, and its box grown by the
    // coplanarity tolerance.
    struct NewTriangle {
        ContactTriangle tri;
        Bounds3 box;
    };

    static uint64_t pairOf(VertexHandle v0, VertexHandle v1) {
        return (uint64_t(uint32_t(v0.idx())) << 32 | uint32_t(v1.idx())) + 1;
    }

    // BaseDecimaterT::is_collapse_legal (its feature test left out: no feature is ever set),
    // and not refused for a crossing before with the same two vertices.
    bool legal(const CollapseInfo& ci) {
        if (m_.status(ci.v0).locked()) return false;
        if (!m_.is_collapse_ok(ci.v0v1)) return false;
        if (ci.vl.is_valid() && ci.vr.is_valid() && m_.find_halfedge(ci.vl, ci.vr).is_valid() &&
            m_.valence(ci.vl) == 3 && m_.valence(ci.vr) == 3)
            return false;
        if (m_.is_boundary(ci.v0)) {
            // A boundary vertex goes only along the boundary, where one ring meets the other.
            if (!m_.is_boundary(ci.v1)) return false;
            if (ci.vl.is_valid() && ci.vr.is_valid()) return false;
        }
        // At least two triangles at v0.
        if (m_.cw_rotated_halfedge_handle(m_.cw_rotated_halfedge_handle(ci.v0v1)) == ci.v0v1)
            return false;
        // Refusals are few: a small map, asked last, costs less than a mark per halfedge.
        if (refused_.empty()) return true;
        const auto it = refused_.find(uint32_t(ci.v0v1.idx()));
        return it == refused_.end() || it->second != pairOf(ci.v0, ci.v1);
    }

    // The collapse's priority (lower first), or kIllegal: see Simplify.h for the rules.
    float priority(const CollapseInfo& ci) const {
        const double error = m_.collapseError(ci.v0v1, ci.v0, ci.v1);
        // The fan of v0 after the move: no fold, and p0 stays near it (once one triangle is
        // near enough, the others need not be measured).
        const Vec3 p0 = toVec(ci.p0), p1 = toVec(ci.p1);
        double nearest = INFINITY;
        const HalfedgeHandle first = m_.halfedge_handle(ci.v0);
        HalfedgeHandle h = first;
        do {
            const FaceHandle f = m_.face_handle(h);
            if (f.is_valid() && f != ci.fl && f != ci.fr) {
                // The triangle (v0, b, c) in its own order.
                const Vec3 b = toVec(m_.point(m_.to_vertex_handle(h)));
                const Vec3 c = toVec(m_.point(m_.to_vertex_handle(m_.next_halfedge_handle(h))));
                const Vec3 before = glm::cross(b - p0, c - p0);
                const Vec3 after = glm::cross(b - p1, c - p1);
                const double lb = glm::length(before), la = glm::length(after);
                if (!(la > 0.0)) return kIllegal;
                if (lb > 0.0 && glm::dot(before, after) < tol::kSimplifyMaxFanTurnCos * lb * la)
                    return kIllegal;
                if (nearest > m_.maxSquared) {
                    const Vec3 gap = closestPointOnTriangle(p0, p1, b, c) - p0;
                    nearest = std::min(nearest, glm::dot(gap, gap));
                }
            }
            h = m_.cw_rotated_halfedge_handle(h);
        } while (h != first);
        if (nearest > m_.maxSquared) return kIllegal;
        return float(error + kLengthPriority * glm::dot(p1 - p0, p1 - p0));
    }

    // DecimaterT::heap_vertex: the vertex's best legal collapse on the heap, or off it.
    void rate(VertexHandle v) {
        float best = FLT_MAX;
        HalfedgeHandle target;
        for (auto voh = m_.voh_iter(v); voh.is_valid(); ++voh) {
            const CollapseInfo ci(m_, *voh);
            if (!legal(ci)) continue;
            const float p = priority(ci);
            if (p >= 0.0f && p < best) {
                best = p;
                target = *voh;
            }
        }
        const size_t i = size_t(v.idx());
        target_[i] = target;
        if (target.is_valid()) {
            priority_[i] = best;
            if (heap_.is_stored(v))
                heap_.update(v);
            else
                heap_.insert(v);
        } else {
            if (heap_.is_stored(v)) heap_.remove(v);
            priority_[i] = -1.0f;
        }
    }

    // A triangle's box, from its corners as kept for the contact test.
    static Bounds3 boxOf(const ContactTriangle& t) {
        Bounds3 box;
        for (const Vec3& p : t.p) box.extend(p);
        return box;
    }

    // A triangle as the contact test takes it, kept for every triangle, and listed in the grid
    // under its box (which its kept corners give back when it is unlisted).
    void store(uint32_t id, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
        faceTriangles_[id] = contactTriangle(p0, p1, p2, limits_.contactTol);
        grid_->insert(id, boxOf(faceTriangles_[id]));
    }
    void store(FaceHandle f) {
        const HalfedgeHandle a = m_.halfedge_handle(f);
        const HalfedgeHandle b = m_.next_halfedge_handle(a);
        store(uint32_t(f.idx()), toVec(m_.point(m_.to_vertex_handle(a))),
              toVec(m_.point(m_.to_vertex_handle(b))),
              toVec(m_.point(m_.to_vertex_handle(m_.next_halfedge_handle(b)))));
    }

    void buildGrid() {
        Bounds3 bounds;
        double length = 0.0;
        for (const VertexHandle v : m_.vertices()) bounds.extend(toVec(m_.point(v)));
        for (const auto& tri : limits_.obstacles)
            for (const Vec3& p : tri) bounds.extend(p);
        for (const auto e : m_.edges()) length += m_.calc_edge_length(e);
        const double cell = m_.n_edges() > 0 ? kGridCellEdges * length / double(m_.n_edges()) : 0.0;
        grid_.emplace(bounds.lo, cell > 0.0 ? cell : 1.0);
        // The piece's triangles by face index, then the obstacles after them.
        const size_t faces = m_.n_faces();
        faceTriangles_.resize(faces + limits_.obstacles.size());
        for (const FaceHandle f : m_.faces())
            if (!m_.status(f).deleted()) store(f);
        for (size_t i = 0; i < limits_.obstacles.size(); ++i) {
            const auto& [p0, p1, p2] = limits_.obstacles[i];
            store(uint32_t(faces + i), p0, p1, p2);
        }
    }

    // Before a collapse: v0's triangles leave the grid (two go, the others change).
    void unlistFan(VertexHandle v0) {
        changed_.clear();
        for (auto vf = m_.vf_iter(v0); vf.is_valid(); ++vf) {
            changed_.push_back(*vf);
            grid_->remove(uint32_t(vf->idx()), boxOf(faceTriangles_[size_t(vf->idx())]));
        }
    }
    // After it: those that remain, at their new corners.
    void relistFan() {
        for (const FaceHandle f : changed_)
            if (!m_.status(f).deleted()) store(f);
    }

    // Whether the collapse's new fan (v0's triangles other than fl and fr, with v1 for v0)
    // neither crosses nor overlaps another triangle: one of the fan itself or one whose box
    // comes within the coplanarity tolerance of a new triangle's (the triangles at v0 now are
    // replaced, so not tested). Always true when not checking.
    bool keepsClear(const CollapseInfo& ci) {
        if (!checking_) return true;
        made_.clear();
        fan_.clear();
        Bounds3 near;  // of the grown boxes of the new triangles
        const Vec3 p1 = toVec(ci.p1);
        const HalfedgeHandle first = m_.halfedge_handle(ci.v0);
        HalfedgeHandle h = first;
        do {
            const FaceHandle f = m_.face_handle(h);
            if (f.is_valid()) {
                fan_.push_back(uint32_t(f.idx()));
                if (f != ci.fl && f != ci.fr) {
                    const Vec3 b = toVec(m_.point(m_.to_vertex_handle(h)));
                    const Vec3 c = toVec(m_.point(m_.to_vertex_handle(m_.next_halfedge_handle(h))));
                    Bounds3 box;
                    box.extend(p1);
                    box.extend(b);
                    box.extend(c);
                    box.lo -= Vec3(limits_.flatTol);
                    box.hi += Vec3(limits_.flatTol);
                    near.extend(box);
                    made_.push_back({contactTriangle(p1, b, c, limits_.contactTol), box});
                }
            }
            h = m_.cw_rotated_halfedge_handle(h);
        } while (h != first);
        // The new triangles among themselves.
        for (size_t i = 0; i < made_.size(); ++i)
            for (size_t j = i + 1; j < made_.size(); ++j)
                if (!overlap(made_[i].box, made_[j].box).empty() &&
                    meets(made_[i].tri, made_[j].tri)) {
                    ++stats_.refusedCrossing;
                    return false;
                }
        // Every other triangle whose box meets a new triangle's, once each (sorted by index
        // rather than marked per triangle: the marks' random reads cost more than the sort).
        candidates_.clear();
        grid_->forEachNear(near, [&](const BoxGrid::Entry& e) {
            for (const NewTriangle& n : made_)
                if (e.overlaps(n.box)) {
                    candidates_.push_back(e);
                    return;
                }
        });
        const auto byId = [](const BoxGrid::Entry& a, const BoxGrid::Entry& b) {
            return a.id < b.id;
        };
        std::sort(candidates_.begin(), candidates_.end(), byId);
        std::sort(fan_.begin(), fan_.end());
        // Their triangles are scattered in memory and their cache misses dominate the check:
        // ask for all of them before testing any (bench/README.md, self-intersections in
        // simplification).
        for (const BoxGrid::Entry& e : candidates_) __builtin_prefetch(&faceTriangles_[e.id].n);
        uint32_t last = UINT32_MAX;
        for (const BoxGrid::Entry& e : candidates_) {
            if (e.id == last) continue;
            last = e.id;
            if (std::binary_search(fan_.begin(), fan_.end(), e.id)) continue;
            for (const NewTriangle& n : made_)
                if (e.overlaps(n.box) && meets(n.tri, faceTriangles_[e.id])) {
                    ++stats_.refusedCrossing;
                    return false;
                }
        }
        return true;
    }

    // Whether two triangles of the mesh (as it is or would be after the collapse) cross or
    // overlap: triangleContact, after a shortcut for the commonest pair, neighbours across an
    // edge that face the same way. Sharing an edge, they meet only along it or, coplanar, where
    // their interiors overlap; in a consistently oriented mesh they run the edge in opposite
    // directions, and then normals less than 90 degrees apart put their third corners on
    // opposite sides of it, where triangleContact's coplanar test finds them separated too.
    bool meets(const ContactTriangle& a, const ContactTriangle& b) const {
        if (glm::dot(a.n, b.n) > 0.0) {
            int shared = 0;
            for (const Vec3& p : a.p) shared += p == b.p[0] || p == b.p[1] || p == b.p[2];
            if (shared == 2) return false;
        }
        return triangleContact(a, b, limits_.contactTol, limits_.flatTol) != TriangleContact::None;
    }

    OmMesh& m_;
    const CollapseLimits& limits_;
    DecimateStats& stats_;
    const bool checking_;
    // Per vertex: its best collapse, that collapse's priority, its place in the heap.
    std::vector<HalfedgeHandle> target_;
    std::vector<float> priority_;
    std::vector<int> heapPosition_;
    OpenMesh::Utils::HeapT<VertexHandle, HeapInterface> heap_;
    // The crossing check: the triangles in a grid and as tested (the obstacles after the
    // piece's), per refused halfedge the (v0, v1) pair it was refused for.
    std::optional<BoxGrid> grid_;
    std::vector<ContactTriangle> faceTriangles_;
    std::unordered_map<uint32_t, uint64_t> refused_;
    std::vector<FaceHandle> changed_;  // the triangles at v0 of the collapse being made
    // keepsClear's scratch: the triangles at v0 (by index), the new ones, those near them.
    std::vector<uint32_t> fan_;
    std::vector<NewTriangle> made_;
    std::vector<BoxGrid::Entry> candidates_;

    static constexpr float kIllegal = -1.0f;  // ModBaseT::ILLEGAL_COLLAPSE
};

}  // namespace

bool decimate(Piece& piece, const CollapseLimits& limits, DecimateStats* stats) {
    OmMesh om;
    om.maxSquared = limits.maxDeviation * limits.maxDeviation;
    std::vector<OmMesh::VertexHandle> handles;
    handles.reserve(piece.positions.size());
    for (size_t i = 0; i < piece.positions.size(); ++i) {
        const Vec3& p = piece.positions[i];
        handles.push_back(om.add_vertex(OmMesh::Point(p.x, p.y, p.z)));
        om.property(om.quadrics, handles.back()) = piece.quadrics[i];
    }
    OpenMesh::FPropHandleT<uint32_t> material;
    om.add_property(material);
    for (size_t t = 0; t < piece.triangles.size(); ++t) {
        const auto& tri = piece.triangles[t];
        const auto f = om.add_face(handles[tri[0]], handles[tri[1]], handles[tri[2]]);
        if (!f.is_valid()) return false;
        om.property(material, f) = piece.materials[t];
    }
    for (size_t i = 0; i < handles.size(); ++i)
        if (piece.locked[i]) om.status(handles[i]).set_locked(true);
    DecimateStats local;
    Collapser(om, limits, stats ? *stats : local).run();
    // Kept vertices in their input order.
    Piece out;
    std::vector<uint32_t> index(handles.size(), UINT32_MAX);
    for (size_t i = 0; i < handles.size(); ++i) {
        if (om.status(handles[i]).deleted()) continue;
        index[i] = uint32_t(out.positions.size());
        out.positions.push_back(piece.positions[i]);
        out.quadrics.push_back(om.property(om.quadrics, handles[i]));
        out.locked.push_back(piece.locked[i]);
        out.source.push_back(piece.source[i]);
    }
    for (const auto f : om.faces()) {
        if (om.status(f).deleted()) continue;
        std::array<uint32_t, 3> tri{};
        int c = 0;
        for (const auto v : om.fv_range(f)) tri[size_t(c++)] = index[size_t(v.idx())];
        out.triangles.push_back(tri);
        out.materials.push_back(om.property(material, f));
    }
    piece = std::move(out);
    return true;
}

}  // namespace csg
