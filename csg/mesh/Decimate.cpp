#include "csg/mesh/Decimate.h"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>
#include <OpenMesh/Tools/Utils/HeapT.hh>

#include <algorithm>
#include <cfloat>
#include <vector>

#include "csg/Tolerances.h"
#include "csg/mesh/TriangleBvh.h"

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
// The mesh type the decimation runs on. It asks this type whether a collapse keeps the mesh a
// 2-manifold (is_collapse_ok), for every candidate halfedge of every re-rated vertex, then
// asks for a priority. OpenMesh 9.0's TriConnectivity::is_collapse_ok allocates and looks a
// property up by name on each call (on csg_grid3's grid mesh that was over half of
// decimation); this one makes the same tests with a mark per vertex that a counter clears, and
// first the cheap bounds that reject most candidates (the quadric at the kept vertex, the
// valence cap), so the link condition and the fan run only for the rest. valence and
// find_halfedge shadow OpenMesh's out-of-line versions. Walks around a vertex step from one
// outgoing halfedge to the next by OpenMesh's inline cw_rotated_halfedge_handle (the next
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
        // The edges v1-vl and vl-v0 (and v0-vr, vr-v1) must not both be boundary edges.
        VertexHandle vl, vr;
        if (!is_boundary(v0v1)) {
            const HalfedgeHandle h1 = next_halfedge_handle(v0v1), h2 = next_halfedge_handle(h1);
            vl = to_vertex_handle(h1);
            if (is_boundary(opposite_halfedge_handle(h1)) &&
                is_boundary(opposite_halfedge_handle(h2)))
                return false;
        }
        if (!is_boundary(v1v0)) {
            const HalfedgeHandle h1 = next_halfedge_handle(v1v0), h2 = next_halfedge_handle(h1);
            vr = to_vertex_handle(h1);
            if (is_boundary(opposite_halfedge_handle(h1)) &&
                is_boundary(opposite_halfedge_handle(h2)))
                return false;
        }
        if (vl == vr) return false;
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
// heap, the same order of rating, popping and re-rating, so the same collapses), written out so
// that the loop itself can be changed.
class Collapser {
public:
    explicit Collapser(OmMesh& mesh) : m_(mesh), heap_(HeapInterface{this}) {}

    void run() {
        const size_t nv = m_.n_vertices();
        target_.assign(nv, HalfedgeHandle());
        priority_.assign(nv, -1.0f);
        heapPosition_.assign(nv, -1);
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
            support.clear();
            for (auto vv = m_.vv_iter(ci.v0); vv.is_valid(); ++vv) support.push_back(*vv);
            m_.collapse(v0v1);
            m_.property(m_.quadrics, ci.v1) += m_.property(m_.quadrics, ci.v0);
            m_.forgetCollapseError();
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
    // BaseDecimaterT::is_collapse_legal (its feature test left out: no feature is ever set).
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
        return m_.cw_rotated_halfedge_handle(m_.cw_rotated_halfedge_handle(ci.v0v1)) != ci.v0v1;
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

    OmMesh& m_;
    // Per vertex: its best collapse, that collapse's priority, its place in the heap.
    std::vector<HalfedgeHandle> target_;
    std::vector<float> priority_;
    std::vector<int> heapPosition_;
    OpenMesh::Utils::HeapT<VertexHandle, HeapInterface> heap_;

    static constexpr float kIllegal = -1.0f;  // ModBaseT::ILLEGAL_COLLAPSE
};

}  // namespace

bool decimate(Piece& piece, double maxDeviation) {
    OmMesh om;
    om.maxSquared = maxDeviation * maxDeviation;
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
    Collapser(om).run();
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
