#include "csg/mesh/DualContour.h"

#include <algorithm>
#include <array>
#include <vector>

#include "csg/Tolerances.h"
#include "csg/mesh/CellTopology.h"
#include "csg/mesh/ParallelFor.h"
#include "csg/mesh/Qef.h"

namespace csg {

namespace {

using Node3 = std::array<int, 3>;

// The Hermite sample of one grid edge: the ray's crossing, or, when the ray saw none although
// the corner signs differ (a node within rounding of a face), the midpoint with the edge's
// own direction as normal.
struct EdgeSample {
    Vec3 point;
    Vec3 normal;
    uint32_t material = 0;
    bool measured = true;
};

class Contourer {
public:
    Contourer(const HermiteGrid& grid, DualContourStats& stats, int threads)
        : grid_(grid), spec_(grid.spec()), stats_(stats), workers_(resolveThreads(threads)) {}

    TriangleMesh run() {
        collectActiveCells();
        placeSheetVertices();
        for (const uint64_t cell : active_) fansOfCell(cell);
        finishNormals();
        return std::move(mesh_);
    }

private:
    uint64_t cellIndex(const Node3& c) const {
        return uint64_t(c[0]) + uint64_t(spec_.nodes[0]) *
                                    (uint64_t(c[1]) + uint64_t(spec_.nodes[1]) * uint64_t(c[2]));
    }
    Node3 cellNode(uint64_t index) const {
        const uint64_t nx = uint64_t(spec_.nodes[0]), ny = uint64_t(spec_.nodes[1]);
        return {int(index % nx), int((index / nx) % ny), int(index / (nx * ny))};
    }
    uint8_t cellMask(const Node3& c) const {
        uint8_t mask = 0;
        for (int corner = 0; corner < 8; ++corner)
            if (grid_.inside(c[0] + (corner & 1), c[1] + ((corner >> 1) & 1),
                             c[2] + ((corner >> 2) & 1)))
                mask = uint8_t(mask | (1u << corner));
        return mask;
    }
    bool inside(const Node3& n) const { return grid_.inside(n[0], n[1], n[2]); }

    // How far apart vertices are kept in a cell or face whose smallest edge is width: the
    // grid spacing's tol::kMeshVertexSeparation, which stays clear of float rounding in a GLB,
    // or a quarter of a thinner cell (one through a thin gap, ThinFeatures.h: at least
    // kThinMinWidth h / 2 wide, so a quarter of it is still ~10 float steps of a coordinate
    // 1000 h from the origin).
    double separation(double width) const {
        return std::min(0.25 * width, tol::kMeshVertexSeparation * spec_.h);
    }

    // missing counts the sign changes without a crossing (DualContourStats::missingCrossings).
    EdgeSample sample(int axis, const Node3& node, uint64_t& missing) const {
        Node3 next = node;
        ++next[axis];
        if (const Crossing* x = grid_.crossing(axis, node)) {
            // A crossing within rounding of a node (the surface passes through it; among
            // millions of nodes some do) would meet the crossings of that node's other edges
            // at one float position in a GLB: keep it a separation inside its own edge.
            const double lo = spec_.coords[size_t(axis)][size_t(node[axis])];
            const double hi = spec_.coords[size_t(axis)][size_t(next[axis])];
            const double apart = separation(hi - lo);
            Vec3 p = x->point;
            p[axis] = std::clamp(p[axis], lo + apart, hi - apart);
            return {p, x->normal, x->material, true};
        }
        ++missing;
        EdgeSample s;
        s.point =
            0.5 * (spec_.node(node[0], node[1], node[2]) + spec_.node(next[0], next[1], next[2]));
        s.normal = Vec3(0.0);
        s.normal[axis] = inside(node) ? 1.0 : -1.0;
        s.measured = false;
        return s;
    }

    // Step 1: the cells with corners of both signs, in index order (deterministic output):
    // each layer of cells on a worker, the layers joined in order.
    void collectActiveCells() {
        const int layers = spec_.nodes[2] - 1;
        std::vector<std::vector<uint64_t>> perLayer(size_t(std::max(layers, 0)));
        parallelFor(uint64_t(std::max(layers, 0)), workers_, [&](int, uint64_t layer) {
            const int k = int(layer);
            for (int j = 0; j + 1 < spec_.nodes[1]; ++j)
                for (int i = 0; i + 1 < spec_.nodes[0]; ++i) {
                    const uint8_t mask = cellMask({i, j, k});
                    if (mask != 0 && mask != 0xff) perLayer[layer].push_back(cellIndex({i, j, k}));
                }
        });
        size_t total = 0;
        for (const auto& layer : perLayer) total += layer.size();
        active_.reserve(total);
        for (auto& layer : perLayer) {
            active_.insert(active_.end(), layer.begin(), layer.end());
            layer = {};
        }
        stats_.activeCells = active_.size();
    }

    // Step 2: one QEF vertex per sheet of every active cell. The vertices' indices follow the
    // cells' order (counted first), so the cells are placed on all workers into their slots.
    void placeSheetVertices() {
        // Indexed by cell: only active cells' entries are ever written or read.
        sheetBase_.resize(spec_.nodeCount());
        uint32_t next = 0;
        for (const uint64_t index : active_) {
            sheetBase_[index] = next;
            next += uint32_t(cellCycles(cellMask(cellNode(index))).count);
        }
        mesh_.positions.resize(next);
        mesh_.normals.assign(next, Vec3(0.0));
        stats_.sheetVertices = next;
        std::vector<uint64_t> missing(size_t(workers_), 0);
        constexpr uint64_t kChunk = 1024;
        parallelFor((active_.size() + kChunk - 1) / kChunk, workers_, [&](int w, uint64_t chunk) {
            const size_t end = std::min<size_t>(active_.size(), (chunk + 1) * kChunk);
            for (size_t i = chunk * kChunk; i < end; ++i)
                placeSheetVerticesOf(active_[i], missing[size_t(w)]);
        });
        for (const uint64_t m : missing) stats_.missingCrossings += m;
    }

    void placeSheetVerticesOf(uint64_t index, uint64_t& missing) {
        const Node3 c = cellNode(index);
        const CellCycles& cycles = cellCycles(cellMask(c));
        // The cell inset a hair, so sheet vertices of neighbouring cells (say both clamped
        // onto a crease lying in their shared face) stay distinct points, also as floats.
        const double width = spec_.cellMinWidth(c[0], c[1], c[2]);
        const Vec3 inset(separation(width));
        const Bounds3 box{spec_.node(c[0], c[1], c[2]) + inset,
                          spec_.node(c[0] + 1, c[1] + 1, c[2] + 1) - inset};
        Vec3 placed[4], mass[4];  // a cell has at most 4 sheets
        for (int q = 0; q < cycles.count; ++q) {
            Qef3 qef;
            for (int e = 0; e < 12; ++e) {
                if (cycles.edgeCycle[size_t(e)] != q) continue;
                const int a = e / 4;
                Node3 n = c;
                n[(a + 1) % 3] += e & 1;
                n[(a + 2) % 3] += (e >> 1) & 1;
                const EdgeSample s = sample(a, n, missing);
                qef.add(s.point, s.normal);
            }
            placed[q] = glm::clamp(qef.solve(box), box.lo, box.hi);
            mass[q] = qef.massPoint();
        }
        // Two sheets whose features meet at one point (solids touching along an edge, a
        // non-manifold part) would share a position: pull each toward its own patch, so the
        // mesh is a manifold in space too, not only in its indices.
        const double apart = separation(width);
        for (int q = 0; q < cycles.count; ++q) {
            for (int o = 0; o < cycles.count; ++o) {
                if (o == q || glm::length(placed[q] - placed[o]) > 2.0 * apart) continue;
                const Vec3 toward = mass[q] - placed[q];
                const double len = glm::length(toward);
                if (len > 0.0) placed[q] += toward * (std::min(len, 4.0 * apart) / len);
            }
            mesh_.positions[sheetBase_[index] + uint32_t(q)] = placed[q];
        }
    }

    uint32_t addVertex(const Vec3& p, const Vec3& n) {
        mesh_.positions.push_back(p);
        mesh_.normals.push_back(n);
        return uint32_t(mesh_.positions.size() - 1);
    }

    uint32_t sheetVertex(const Node3& cell, int localEdge) {
        const uint32_t base = sheetBase_[cellIndex(cell)];
        return base + uint32_t(cellCycles(cellMask(cell)).edgeCycle[size_t(localEdge)]);
    }

    // The vertex on the face between two cells of edge (a, n0)'s ring, or kNone for a straight
    // face curve. g is the axis the two cells differ on; h the other ring axis, dh its offset.
    static constexpr uint32_t kNone = UINT32_MAX;
    static constexpr uint32_t kUnknown = UINT32_MAX - 1;  // not decided yet

    // The face vertex decided for segment of the face at faceMin perpendicular to g. The fans
    // of a cell at layer k (node z index) only meet faces at layers k - 1 and k, and cells come
    // in layer order, so two layers of slots suffice; a slot layer is reset when it is reused
    // for a new layer (only its written slots).
    uint32_t& faceSlot(const Node3& faceMin, int g, int segment) {
        const int z = faceMin[2];
        FaceLayer& layer = faceLayers_[size_t(z & 1)];
        if (layer.z != z) {
            if (layer.slots.empty())
                layer.slots.assign(size_t(spec_.nodes[0]) * size_t(spec_.nodes[1]) * 6, kUnknown);
            for (const uint32_t i : layer.written) layer.slots[i] = kUnknown;
            layer.written.clear();
            layer.z = z;
        }
        const uint32_t i =
            uint32_t(((uint64_t(faceMin[0]) + uint64_t(spec_.nodes[0]) * uint64_t(faceMin[1])) * 3 +
                      uint64_t(g)) *
                         2 +
                     uint64_t(segment));
        if (layer.slots[i] == kUnknown) layer.written.push_back(i);
        return layer.slots[i];
    }
    uint32_t faceVertex(int a, const Node3& n0, int g, int h, int dh) {
        // Step 1: the face, its corners' signs, and which of its edges is ours.
        Node3 faceMin = n0;
        faceMin[h] += dh;
        const int u = (g + 1) % 3, v = (g + 2) % 3;
        std::array<bool, 4> corner;
        for (int dv = 0; dv < 2; ++dv)
            for (int du = 0; du < 2; ++du) {
                Node3 p = faceMin;
                p[u] += du;
                p[v] += dv;
                corner[size_t(du + 2 * dv)] = inside(p);
            }
        const int edgeAxis = a == u ? 0 : 1;
        const int segment = faceSegment(corner, edgeAxis, -dh);
        uint32_t& known = faceSlot(faceMin, g, segment);
        if (known != kUnknown) return known;

        // Step 2: the partner edge of the same face curve.
        int partnerAxis = -1, partnerOffset = -1;
        for (int ax = 0; ax < 2; ++ax)
            for (int o = 0; o < 2; ++o) {
                if (ax == edgeAxis && o == -dh) continue;
                const int c0 = ax == 0 ? 2 * o : o, c1 = ax == 0 ? 1 + 2 * o : o + 2;
                if (corner[size_t(c0)] == corner[size_t(c1)]) continue;
                if (faceSegment(corner, ax, o) == segment) {
                    partnerAxis = ax;
                    partnerOffset = o;
                }
            }
        Node3 partnerNode = faceMin;
        partnerNode[partnerAxis == 0 ? v : u] += partnerOffset;
        const EdgeSample s0 = sample(a, n0, stats_.missingCrossings);
        const EdgeSample s1 =
            sample(partnerAxis == 0 ? u : v, partnerNode, stats_.missingCrossings);

        // Step 3: bend the curve where the tangent lines meet; an ambiguous face always gets a
        // vertex, so two curves on one face never join the same two sheet vertices twice.
        const bool ambiguous = corner[0] == corner[3] && corner[1] == corner[2];
        const Vec3 lo3 = spec_.node(faceMin[0], faceMin[1], faceMin[2]);
        Node3 faceMax = faceMin;
        ++faceMax[u];
        ++faceMax[v];
        const Vec3 hi3 = spec_.node(faceMax[0], faceMax[1], faceMax[2]);
        const Vec2 lo(lo3[u], lo3[v]), hi(hi3[u], hi3[v]);
        Vec3 crease;
        uint32_t vertex = kNone;
        // A crease point (almost) on one of the crossings adds nothing but a sliver triangle
        // whose corners round to one point when written as float: skip it.
        const double apart = separation(std::min(hi[0] - lo[0], hi[1] - lo[1]));
        if (s0.measured && s1.measured &&
            creaseOnFace(s0.point, s0.normal, s1.point, s1.normal, u, v, lo, hi, crease) &&
            glm::length(crease - s0.point) > apart && glm::length(crease - s1.point) > apart) {
            crease[g] = lo3[g];
            vertex = addVertex(crease, Vec3(0.0));
        } else if (ambiguous) {
            Vec3 mid = 0.5 * (s0.point + s1.point);
            mid[g] = lo3[g];
            vertex = addVertex(mid, Vec3(0.0));
        }
        if (vertex != kNone) ++stats_.faceVertices;
        known = vertex;
        return vertex;
    }

    // Step 3: the fan of each crossed edge that starts at this cell's minimum corner.
    void fansOfCell(uint64_t index) {
        const Node3 n0 = cellNode(index);
        for (int a = 0; a < 3; ++a) {
            Node3 n1 = n0;
            ++n1[a];
            const bool in0 = inside(n0);
            if (in0 == inside(n1)) continue;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const EdgeSample s = sample(a, n0, stats_.missingCrossings);
            const uint32_t center = addVertex(s.point, s.normal);

            // The ring: cells at (db, dc) counter-clockwise about +a, face vertices between.
            static constexpr int kRing[4][2] = {{-1, -1}, {0, -1}, {0, 0}, {-1, 0}};
            uint32_t ring[8];
            int count = 0;
            for (int q = 0; q < 4; ++q) {
                Node3 cell = n0;
                cell[b] += kRing[q][0];
                cell[c] += kRing[q][1];
                ring[count++] =
                    sheetVertex(cell, 4 * a + (kRing[q][0] < 0) + 2 * (kRing[q][1] < 0));
                const int* next = kRing[(q + 1) % 4];
                const bool differOnB = next[0] != kRing[q][0];
                const int g = differOnB ? b : c, h = differOnB ? c : b;
                const int dh = differOnB ? kRing[q][1] : kRing[q][0];
                const uint32_t f = faceVertex(a, n0, g, h, dh);
                if (f != kNone) ring[count++] = f;
            }

            // Outward is +a when the edge leaves the solid going up the axis.
            for (int t = 0; t < count; ++t) {
                uint32_t p = ring[t], q = ring[(t + 1) % count];
                if (!in0) std::swap(p, q);
                mesh_.triangles.push_back({center, p, q});
                mesh_.triangleMaterial.push_back(s.material);
            }
        }
    }

    // Step 4: normals of QEF and face vertices from their triangles (area-weighted); crossing
    // vertices keep the exact normal.
    void finishNormals() {
        std::vector<Vec3> sum(mesh_.positions.size(), Vec3(0.0));
        for (const auto& tri : mesh_.triangles) {
            const Vec3 n = glm::cross(mesh_.positions[tri[1]] - mesh_.positions[tri[0]],
                                      mesh_.positions[tri[2]] - mesh_.positions[tri[0]]);
            for (const uint32_t corner : tri) sum[corner] += n;
        }
        for (size_t i = 0; i < sum.size(); ++i) {
            if (mesh_.normals[i] != Vec3(0.0)) continue;
            const double len = glm::length(sum[i]);
            mesh_.normals[i] = len > 0.0 ? sum[i] / len : Vec3(0.0, 0.0, 1.0);
        }
    }

    const HermiteGrid& grid_;
    const GridSpec& spec_;
    DualContourStats& stats_;
    const int workers_;
    TriangleMesh mesh_;
    std::vector<uint64_t> active_;
    std::vector<uint32_t> sheetBase_;  // per cell index: its first sheet vertex
    struct FaceLayer {
        int z = -1;
        std::vector<uint32_t> slots;    // per (i, j, axis, segment): see faceSlot
        std::vector<uint32_t> written;  // slots set since the layer was last reset
    };
    std::array<FaceLayer, 2> faceLayers_;
};

}  // namespace

TriangleMesh dualContour(const HermiteGrid& grid, DualContourStats* stats, int threads) {
    DualContourStats local;
    DualContourStats& s = stats ? *stats : local;
    s.cells = grid.spec().cellCount();
    s.thinEdges = grid.thinEdges();
    s.thinAt = grid.thinAt();
    return Contourer(grid, s, threads).run();
}

}  // namespace csg
