#include "csg/mesh/Simplify.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
// QuadricT.hh uses vector_traits without including it: after the mesh header.
#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <vector>

#include "csg/Tolerances.h"
#include "csg/mesh/ParallelFor.h"
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

using Quadric = OpenMesh::Geometry::Quadricd;

// A collapse may leave the kept vertex with at most this many neighbours. The decimater
// re-rates every edge around the kept vertex after each collapse, at a cost that grows with
// the square of its valence, so letting a flat face shrink to one fan of hundreds of
// triangles makes simplification slower than meshing; 24 still lets a flat face coarsen to
// triangles ~24 grid cells across wherever its outline allows.
constexpr unsigned kMaxValence = 24;
// Secondary priority, edge length squared against the quadric's squared distance (unit:
// relative): among equally flat collapses the shortest edge goes first, so a plane coarsens
// evenly instead of growing long slivers from one corner.
constexpr double kLengthPriority = 1e-4;

// The mesh type the decimater is instantiated with. It asks this type whether a collapse keeps
// the mesh a 2-manifold (is_collapse_ok), for every candidate halfedge of every re-rated vertex,
// then asks the module for a priority. OpenMesh 9.0's TriConnectivity::is_collapse_ok allocates
// and looks a property up by name on each call (on csg_grid3's grid mesh that was over half of
// decimation); this one makes the same tests with a mark per vertex that a counter clears, and
// first the cheap bounds of the module that reject most candidates (the quadric at the kept
// vertex, the valence cap), so the link condition and the fan run only for the rest. A
// candidate is legal and rated exactly when it was before (the same tests, in another order).
// valence and find_halfedge shadow OpenMesh's out-of-line versions for the decimater's own
// tests. Walks around a vertex step from one outgoing halfedge to the next by OpenMesh's inline
// cw_rotated_halfedge_handle (the next halfedge of the opposite one).
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
    // the decimater asks for a collapse's priority (heap_vertex) only right after
    // is_collapse_ok passed that same halfedge. A collapse changes quadrics only in
    // postprocess_collapse, which forgets the value; the fallback never runs but keeps the
    // answer right if the decimater's call order ever changes.
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
        // The module's bound on the kept vertex (ModSurfaceDeviationT::collapse_priority).
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

Vec3 toVec(const OmMesh::Point& p) {
    return {p[0], p[1], p[2]};
}

// The one priority module: see Simplify.h for the rules it enforces. The valence cap and the
// quadric bound are tested by OmMesh::is_collapse_ok, which the decimater asks first.
template <class MeshT>
class ModSurfaceDeviationT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
    DECIMATING_MODULE(ModSurfaceDeviationT, MeshT, SurfaceDeviation);

    explicit ModSurfaceDeviationT(MeshT& mesh) : Base(mesh, false) {}

    float collapse_priority(const CollapseInfo& ci) override {
        const MeshT& m = Base::mesh();
        const double error = m.collapseError(ci.v0v1, ci.v0, ci.v1);
        // The fan of v0 after the move: no fold, and p0 stays near it (once one triangle is
        // near enough, the others need not be measured).
        const Vec3 p0 = toVec(ci.p0), p1 = toVec(ci.p1);
        double nearest = INFINITY;
        const auto first = m.halfedge_handle(ci.v0);
        auto h = first;
        do {
            const auto f = m.face_handle(h);
            if (f.is_valid() && f != ci.fl && f != ci.fr) {
                // The triangle (v0, b, c) in its own order.
                const Vec3 b = toVec(m.point(m.to_vertex_handle(h)));
                const Vec3 c = toVec(m.point(m.to_vertex_handle(m.next_halfedge_handle(h))));
                const Vec3 before = glm::cross(b - p0, c - p0);
                const Vec3 after = glm::cross(b - p1, c - p1);
                const double lb = glm::length(before), la = glm::length(after);
                if (!(la > 0.0)) return float(Base::ILLEGAL_COLLAPSE);
                if (lb > 0.0 && glm::dot(before, after) < tol::kSimplifyMaxFanTurnCos * lb * la)
                    return float(Base::ILLEGAL_COLLAPSE);
                if (nearest > m.maxSquared) {
                    const Vec3 gap = closestPointOnTriangle(p0, p1, b, c) - p0;
                    nearest = std::min(nearest, glm::dot(gap, gap));
                }
            }
            h = m.cw_rotated_halfedge_handle(h);
        } while (h != first);
        if (nearest > m.maxSquared) return float(Base::ILLEGAL_COLLAPSE);
        return float(error + kLengthPriority * glm::dot(p1 - p0, p1 - p0));
    }

    void postprocess_collapse(const CollapseInfo& ci) override {
        MeshT& m = Base::mesh();
        m.property(m.quadrics, ci.v1) += m.property(m.quadrics, ci.v0);
        m.forgetCollapseError();
    }
};

// A part of the mesh to decimate: its vertices (positions, quadrics, locks, where each came from)
// and triangles (local vertex indices, materials).
struct Piece {
    std::vector<Vec3> positions;
    std::vector<Quadric> quadrics;
    std::vector<uint8_t> locked;
    std::vector<uint32_t> source;  // the input's vertex index
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<uint32_t> materials;
};

// Decimates a piece in place: the kept vertices (with their merged quadrics) and the triangles
// left. False when OpenMesh refuses a face (a piece that is not a 2-manifold with boundary);
// the piece is then unchanged.
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
    {
        using Decimater = OpenMesh::Decimater::DecimaterT<OmMesh>;
        Decimater decimater(om);
        ModSurfaceDeviationT<OmMesh>::Handle deviation;
        decimater.add(deviation);
        if (!decimater.initialize()) return false;
        decimater.decimate();
    }
    // Kept vertices in their input order (garbage collection keeps the order of survivors).
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

// Triangles per block: below twice this the mesh is decimated in one piece (blocks would not
// pay for their borders). The count of blocks depends on the mesh only, not on the workers, so
// a part gives the same mesh on every machine.
constexpr size_t kTrianglesPerBlock = 150'000;
// At most this many blocks: slabs thin enough that the locked strips along their borders (two
// rings on each side) hold a large share of the mesh leave too much to the pass over the whole.
constexpr size_t kMaxBlocks = 16;

// The blocks pass: triangles split into slabs along the longest axis of the bounds (equal
// triangle counts), each decimated on its own with the vertices it shares with another slab
// and every neighbour of those locked. An unlocked vertex then has its whole fan and every
// neighbour's whole fan in the slab, so the slab's link condition, fan and quadrics are the
// whole mesh's for every collapse it makes; what the locks held back is left to the pass over
// the whole mesh that follows. Returns the merged mesh as one piece, or nothing when a slab is
// not a 2-manifold with boundary (a vertex pinched at the slab's border).
std::optional<Piece> decimateInBlocks(const Piece& whole, double maxDeviation, int blocks,
                                      int threads) {
    const size_t nv = whole.positions.size(), nt = whole.triangles.size();
    // Step 1: the slab of every triangle, by its first corner along the longest axis.
    Vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vec3& p : whole.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const Vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    std::vector<double> keys(nt);
    for (size_t t = 0; t < nt; ++t) keys[t] = whole.positions[whole.triangles[t][0]][axis];
    std::vector<double> cuts;
    {
        std::vector<double> sorted = keys;
        for (int b = 1; b < blocks; ++b) {
            const auto at = sorted.begin() + ptrdiff_t(nt * size_t(b) / size_t(blocks));
            std::nth_element(sorted.begin(), at, sorted.end());
            cuts.push_back(*at);
        }
        std::sort(cuts.begin(), cuts.end());
    }
    std::vector<uint16_t> slab(nt);
    for (size_t t = 0; t < nt; ++t)
        slab[t] = uint16_t(std::upper_bound(cuts.begin(), cuts.end(), keys[t]) - cuts.begin());

    // Step 2: a vertex's owner is its triangles' slab, or kShared when they are in several;
    // the locks: shared vertices, their neighbours, and the input's locks (material borders).
    constexpr uint16_t kNone = UINT16_MAX, kShared = UINT16_MAX - 1;
    std::vector<uint16_t> owner(nv, kNone);
    for (size_t t = 0; t < nt; ++t)
        for (const uint32_t v : whole.triangles[t]) {
            if (owner[v] == kNone)
                owner[v] = slab[t];
            else if (owner[v] != slab[t])
                owner[v] = kShared;
        }
    std::vector<uint8_t> locked = whole.locked;
    for (size_t t = 0; t < nt; ++t) {
        const auto& tri = whole.triangles[t];
        if (owner[tri[0]] == kShared || owner[tri[1]] == kShared || owner[tri[2]] == kShared)
            for (const uint32_t v : tri) locked[v] = 1;
    }

    // Step 3: the slabs as pieces (local vertex indices), decimated in parallel.
    std::vector<std::vector<uint32_t>> slabTriangles(static_cast<size_t>(blocks));
    for (size_t t = 0; t < nt; ++t) slabTriangles[slab[t]].push_back(uint32_t(t));
    std::vector<Piece> pieces(static_cast<size_t>(blocks));
    {
        std::vector<uint32_t> local(nv);
        std::vector<uint16_t> localSlab(nv, kNone);
        for (int b = 0; b < blocks; ++b) {
            Piece& piece = pieces[size_t(b)];
            for (const uint32_t t : slabTriangles[size_t(b)]) {
                std::array<uint32_t, 3> tri{};
                for (int c = 0; c < 3; ++c) {
                    const uint32_t v = whole.triangles[t][size_t(c)];
                    if (localSlab[v] != uint16_t(b)) {
                        localSlab[v] = uint16_t(b);
                        local[v] = uint32_t(piece.positions.size());
                        piece.positions.push_back(whole.positions[v]);
                        piece.quadrics.push_back(whole.quadrics[v]);
                        piece.locked.push_back(locked[v]);
                        piece.source.push_back(whole.source[v]);
                    }
                    tri[size_t(c)] = local[v];
                }
                piece.triangles.push_back(tri);
                piece.materials.push_back(whole.materials[t]);
            }
        }
    }
    std::atomic<bool> refused{false};
    parallelFor(uint64_t(blocks), threads, [&](int, uint64_t b) {
        if (!decimate(pieces[b], maxDeviation)) refused = true;
    });
    if (refused) return std::nullopt;

    // Step 4: the slabs merged into one piece, vertices indexed as in the input's order of
    // first use; a shared vertex (never moved, never merged into: its neighbours are locked)
    // appears once, its quadric the input's, and the slabs' locks are lifted.
    Piece merged;
    std::vector<uint32_t> index(nv, UINT32_MAX);
    for (const Piece& piece : pieces) {
        std::vector<uint32_t> toMerged(piece.positions.size());
        for (size_t i = 0; i < piece.positions.size(); ++i) {
            const uint32_t from = piece.source[i];
            // whole.source is the identity for the input piece simplify() makes.
            uint32_t& id = index[from];
            if (id == UINT32_MAX) {
                id = uint32_t(merged.positions.size());
                merged.positions.push_back(piece.positions[i]);
                merged.quadrics.push_back(piece.quadrics[i]);
                merged.locked.push_back(whole.locked[from]);
                merged.source.push_back(from);
            }
            toMerged[i] = id;
        }
        for (size_t t = 0; t < piece.triangles.size(); ++t) {
            const auto& tri = piece.triangles[t];
            merged.triangles.push_back({toMerged[tri[0]], toMerged[tri[1]], toMerged[tri[2]]});
            merged.materials.push_back(piece.materials[t]);
        }
    }
    return merged;
}

}  // namespace

TriangleMesh simplify(const TriangleMesh& mesh, double maxDeviation, SimplifyStats* stats,
                      int threads) {
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point t) {
        return std::chrono::duration<double>(Clock::now() - t).count();
    };
    auto phase = Clock::now();
    SimplifyStats local;
    SimplifyStats& s = stats ? *stats : local;
    s = {};
    s.trianglesBefore = s.trianglesAfter = mesh.triangles.size();
    if (mesh.empty() || !(maxDeviation > 0.0)) return mesh;

    // Step 1: the whole mesh as a piece: unweighted plane quadrics (a sum of squared distances,
    // so a bound on it bounds the distance to each merged plane), and vertices on a material
    // border locked (the decimater never removes them).
    const size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
    Piece whole;
    whole.positions = mesh.positions;
    whole.quadrics.assign(nv, Quadric());  // zero: no plane yet
    whole.locked.assign(nv, 0);
    whole.source.resize(nv);
    std::iota(whole.source.begin(), whole.source.end(), 0u);
    whole.triangles = mesh.triangles;
    whole.materials =
        mesh.triangleMaterial.empty() ? std::vector<uint32_t>(nt, 0u) : mesh.triangleMaterial;
    std::vector<uint32_t> firstMaterial(nv, UINT32_MAX);
    for (size_t t = 0; t < nt; ++t) {
        const auto& tri = mesh.triangles[t];
        for (const uint32_t v : tri) {
            if (v >= nv) return mesh;  // not a mesh: left to the checks downstream
            if (firstMaterial[v] == UINT32_MAX)
                firstMaterial[v] = whole.materials[t];
            else if (firstMaterial[v] != whole.materials[t])
                whole.locked[v] = 1;
        }
        const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]],
                   c = mesh.positions[tri[2]];
        const Vec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        if (!(len > 0.0)) continue;
        const Vec3 u = n / len;
        const Quadric q(u.x, u.y, u.z, -glm::dot(u, a));
        for (const uint32_t v : tri) whole.quadrics[v] += q;
    }
    s.buildSeconds = since(phase);
    phase = Clock::now();

    // Step 2: decimate, a big mesh in blocks first (on all workers), then the whole.
    const int blocks = int(std::min(kMaxBlocks, nt / kTrianglesPerBlock));
    Piece piece;
    if (blocks >= 2) {
        if (std::optional<Piece> merged = decimateInBlocks(whole, maxDeviation, blocks, threads)) {
            piece = std::move(*merged);
            s.blocks = blocks;
            s.trianglesAfterBlocks = piece.triangles.size();
        }
        s.blocksSeconds = since(phase);
    }
    if (piece.triangles.empty()) piece = std::move(whole);
    if (!decimate(piece, maxDeviation)) return mesh;  // not manifold: left to the checks downstream
    s.built = true;
    s.decimateSeconds = since(phase);
    phase = Clock::now();

    // Step 3: back to a TriangleMesh, kept vertices with their own normals.
    TriangleMesh out;
    out.positions = std::move(piece.positions);
    if (!mesh.normals.empty()) {
        out.normals.reserve(out.positions.size());
        for (const uint32_t from : piece.source) out.normals.push_back(mesh.normals[from]);
    }
    out.triangles = std::move(piece.triangles);
    if (!mesh.triangleMaterial.empty()) out.triangleMaterial = std::move(piece.materials);
    s.trianglesAfter = out.triangles.size();
    s.extractSeconds = since(phase);
    return out;
}

}  // namespace csg
