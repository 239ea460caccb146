#include "csg/mesh/Simplify.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
// QuadricT.hh uses vector_traits without including it: after the mesh header.
#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "csg/Tolerances.h"

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

// The decimater asks the mesh type it is instantiated with whether a collapse keeps the mesh a
// 2-manifold, for every candidate halfedge of every re-rated vertex. OpenMesh 9.0's
// TriConnectivity::is_collapse_ok allocates and looks a property up by name on each call (on
// csg_grid3's grid mesh that was over half of decimation); this one makes the same tests with
// a mark per vertex that a counter clears.
class OmMesh : public OpenMesh::TriMesh_ArrayKernelT<SimplifyTraits> {
public:
    bool is_collapse_ok(HalfedgeHandle v0v1) {
        if (status(edge_handle(v0v1)).deleted()) return false;
        const HalfedgeHandle v1v0 = opposite_halfedge_handle(v0v1);
        const VertexHandle v0 = to_vertex_handle(v1v0), v1 = to_vertex_handle(v0v1);
        if (status(v0).deleted() || status(v1).deleted()) return false;
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
        // The link condition: the one-rings of v0 and v1 share only vl and vr.
        if (ringMark_.size() < n_vertices()) ringMark_.resize(n_vertices(), 0);
        if (++mark_ == 0) {
            std::fill(ringMark_.begin(), ringMark_.end(), 0u);
            mark_ = 1;
        }
        for (auto it = cvv_iter(v1); it.is_valid(); ++it) ringMark_[size_t(it->idx())] = mark_;
        for (auto it = cvv_iter(v0); it.is_valid(); ++it)
            if (ringMark_[size_t(it->idx())] == mark_ && *it != vl && *it != vr) return false;
        // An edge between two boundary vertices must be a boundary edge.
        return !(is_boundary(v0) && is_boundary(v1) && !is_boundary(v0v1) && !is_boundary(v1v0));
    }

private:
    std::vector<uint32_t> ringMark_;
    uint32_t mark_ = 0;
};

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

Vec3 toVec(const OmMesh::Point& p) {
    return {p[0], p[1], p[2]};
}

// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double distanceSquaredToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    auto sq = [&](const Vec3& q) { return glm::dot(p - q, p - q); };
    if (d1 <= 0.0 && d2 <= 0.0) return sq(a);
    const Vec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return sq(b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return sq(a + ab * (d1 / (d1 - d3)));
    const Vec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return sq(c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return sq(a + ac * (d2 / (d2 - d6)));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
        return sq(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    const double denom = 1.0 / (va + vb + vc);
    return sq(a + ab * (vb * denom) + ac * (vc * denom));
}

// The one priority module: see Simplify.h for the rules it enforces.
template <class MeshT>
class ModSurfaceDeviationT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
    DECIMATING_MODULE(ModSurfaceDeviationT, MeshT, SurfaceDeviation);

    explicit ModSurfaceDeviationT(MeshT& mesh) : Base(mesh, false) { mesh.add_property(quadrics_); }
    ~ModSurfaceDeviationT() override { Base::mesh().remove_property(quadrics_); }

    void setMaxDeviation(double d) { maxSquared_ = d * d; }

    // Unweighted plane quadrics: the error is a sum of squared distances, so a bound on it
    // bounds the distance to each merged plane.
    void initialize() override {
        Mesh& m = Base::mesh();
        for (const auto v : m.vertices()) m.property(quadrics_, v).clear();
        for (const auto f : m.faces()) {
            auto it = m.cfv_iter(f);
            const auto v0 = *it, v1 = *++it, v2 = *++it;
            const Vec3 a = toVec(m.point(v0)), b = toVec(m.point(v1)), c = toVec(m.point(v2));
            const Vec3 n = glm::cross(b - a, c - a);
            const double len = glm::length(n);
            if (!(len > 0.0)) continue;
            const Vec3 u = n / len;
            const OpenMesh::Geometry::Quadricd q(u.x, u.y, u.z, -glm::dot(u, a));
            m.property(quadrics_, v0) += q;
            m.property(quadrics_, v1) += q;
            m.property(quadrics_, v2) += q;
        }
    }

    float collapse_priority(const CollapseInfo& ci) override {
        Mesh& m = Base::mesh();
        // Step 0: the valence the kept vertex would have (v0's and v1's neighbours, less v0, v1
        // themselves and the two neighbours they share).
        if (m.valence(ci.v0) + m.valence(ci.v1) > kMaxValence + 4)
            return float(Base::ILLEGAL_COLLAPSE);
        // Step 1: the kept vertex against every plane merged into it.
        OpenMesh::Geometry::Quadricd q = m.property(quadrics_, ci.v0);
        q += m.property(quadrics_, ci.v1);
        const double error = std::max(0.0, q(ci.p1));
        if (error > maxSquared_) return float(Base::ILLEGAL_COLLAPSE);

        // Step 2: the fan of v0 after the move: no fold, and p0 stays near it.
        const Vec3 p0 = toVec(ci.p0), p1 = toVec(ci.p1);
        double nearest = INFINITY;
        for (auto it = m.cvoh_iter(ci.v0); it.is_valid(); ++it) {
            const auto f = m.face_handle(*it);
            if (!f.is_valid() || f == ci.fl || f == ci.fr) continue;
            // The triangle (v0, b, c) in its own order.
            const Vec3 b = toVec(m.point(m.to_vertex_handle(*it)));
            const Vec3 c = toVec(m.point(m.to_vertex_handle(m.next_halfedge_handle(*it))));
            const Vec3 before = glm::cross(b - p0, c - p0);
            const Vec3 after = glm::cross(b - p1, c - p1);
            const double lb = glm::length(before), la = glm::length(after);
            if (!(la > 0.0)) return float(Base::ILLEGAL_COLLAPSE);
            if (lb > 0.0 && glm::dot(before, after) < tol::kSimplifyMaxFanTurnCos * lb * la)
                return float(Base::ILLEGAL_COLLAPSE);
            nearest = std::min(nearest, distanceSquaredToTriangle(p0, p1, b, c));
        }
        if (nearest > maxSquared_) return float(Base::ILLEGAL_COLLAPSE);
        return float(error + kLengthPriority * glm::dot(p1 - p0, p1 - p0));
    }

    void postprocess_collapse(const CollapseInfo& ci) override {
        Base::mesh().property(quadrics_, ci.v1) += Base::mesh().property(quadrics_, ci.v0);
    }

private:
    OpenMesh::VPropHandleT<OpenMesh::Geometry::Quadricd> quadrics_;
    double maxSquared_ = 0.0;
};

}  // namespace

TriangleMesh simplify(const TriangleMesh& mesh, double maxDeviation, SimplifyStats* stats,
                      int threads) {
    (void)threads;
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    auto phase = Clock::now();
    SimplifyStats local;
    SimplifyStats& s = stats ? *stats : local;
    s = {};
    s.trianglesBefore = s.trianglesAfter = mesh.triangles.size();
    if (mesh.empty() || !(maxDeviation > 0.0)) return mesh;

    // Step 1: the OpenMesh mesh, each vertex and face remembering where it came from.
    OmMesh om;
    OpenMesh::VPropHandleT<uint32_t> sourceVertex;
    OpenMesh::FPropHandleT<uint32_t> material;
    om.add_property(sourceVertex);
    om.add_property(material);
    std::vector<OmMesh::VertexHandle> handles;
    handles.reserve(mesh.positions.size());
    for (uint32_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3& p = mesh.positions[i];
        handles.push_back(om.add_vertex(OmMesh::Point(p.x, p.y, p.z)));
        om.property(sourceVertex, handles.back()) = i;
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const auto f = om.add_face(handles[tri[0]], handles[tri[1]], handles[tri[2]]);
        if (!f.is_valid()) return mesh;  // not manifold: leave it to the checks downstream
        om.property(material, f) = mesh.triangleMaterial.empty() ? 0 : mesh.triangleMaterial[t];
    }
    s.built = true;

    // Step 2: vertices on a material border are locked (the decimater never removes them).
    for (const auto v : om.vertices()) {
        bool first = true, mixed = false;
        uint32_t seen = 0;
        for (const auto f : om.vf_range(v)) {
            const uint32_t id = om.property(material, f);
            mixed |= !first && id != seen;
            seen = id;
            first = false;
        }
        if (mixed) om.status(v).set_locked(true);
    }

    s.buildSeconds = since(phase);
    phase = Clock::now();
    // Step 3: decimate.
    {
        using Decimater = OpenMesh::Decimater::DecimaterT<OmMesh>;
        Decimater decimater(om);
        ModSurfaceDeviationT<OmMesh>::Handle deviation;
        decimater.add(deviation);
        decimater.module(deviation).setMaxDeviation(maxDeviation);
        if (!decimater.initialize()) return mesh;
        decimater.decimate();
    }
    om.garbage_collection();
    s.decimateSeconds = since(phase);
    phase = Clock::now();

    // Step 4: back to a TriangleMesh, kept vertices with their own normals.
    TriangleMesh out;
    out.positions.reserve(om.n_vertices());
    if (!mesh.normals.empty()) out.normals.reserve(om.n_vertices());
    for (const auto v : om.vertices()) {
        const uint32_t from = om.property(sourceVertex, v);
        out.positions.push_back(mesh.positions[from]);
        if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[from]);
    }
    out.triangles.reserve(om.n_faces());
    for (const auto f : om.faces()) {
        std::array<uint32_t, 3> tri{};
        int i = 0;
        for (const auto v : om.fv_range(f)) tri[size_t(i++)] = uint32_t(v.idx());
        out.triangles.push_back(tri);
        if (!mesh.triangleMaterial.empty())
            out.triangleMaterial.push_back(om.property(material, f));
    }
    s.trianglesAfter = out.triangles.size();
    s.extractSeconds = since(phase);
    return out;
}

}  // namespace csg
