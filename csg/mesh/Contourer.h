// Internal to dual contouring (DualContour.h): Contourer, the one class that builds the mesh.
// Its member functions live in one file per part, as libfive's dc/ folder splits its contourer:
//   DualContour.cpp   the uniform contour: active cells, sheet vertices, the fan of each crossed
//                     edge, unfolding, normals, and the rounds of run();
//   OctreeMerge.cpp   the adaptive octree (DualContourOptions::flatTolerance > 0): blocks merged
//                     into one vertex, Ju's topology test, and the fold checks whose blocks the
//                     next round does not merge;
//   FaceVertices.cpp  the vertices on the cell faces between two cells of a ring (crease
//                     points, and the points that keep an ambiguous face's two curves apart).
// One class rather than three: the parts share one round's state (the mesh being built, the
// merged blocks, the face slots) and meet at every crossed edge (fansOfCell asks faceVertex for
// the vertices between its cells and chooseApex for the vertex to fan from), so separate classes
// would only hand that state back and forth.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_set>
#include <utility>
#include <vector>

#include "csg/mesh/DualContour.h"
#include "csg/mesh/HermiteGrid.h"
#include "csg/mesh/TriangleMesh.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg::detail {

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
    Contourer(const HermiteGrid& grid, DualContourStats& stats, const DualContourOptions& options)
        : grid_(grid),
          spec_(grid.spec()),
          stats_(stats),
          workers_(resolveThreads(options.threads)),
          flatTolerance_(options.flatTolerance) {}

    TriangleMesh run();

private:
    static constexpr uint32_t kNoLeaf = UINT32_MAX;
    static constexpr uint32_t kNone = UINT32_MAX;
    static constexpr uint32_t kUnknown = UINT32_MAX - 1;  // not decided yet

    struct BlockState {
        bool mergeable = false;  // may be (part of) one leaf
        bool surface = false;    // holds an active cell
        Vec3 vertex{0.0};        // the merged vertex, when mergeable with surface (level >= 1)
        Vec3 normal{0.0};        // the mean of its sample normals (unit), likewise
    };
    // A merged block (a leaf of the octree).
    struct Leaf {
        Vec3 vertex{0.0};  // its one vertex
        Vec3 normal{0.0};  // the mean of its sample normals (unit)
        uint64_t key = 0;  // its blockKey
        uint32_t top = 0;  // its top block (mergeFlatBlocks)
    };
    // One top block's work on one worker: its leaves and a sample buffer.
    struct TopBlockWork {
        std::vector<Leaf> leaves;
        std::vector<EdgeSample> samples;
    };

    // ---- The grid, the mesh and the samples, used by every part ----
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
    double separation(double width, double fraction = tol::kMeshVertexSeparation) const {
        return std::min(0.25 * width, fraction * spec_.h);
    }

    // The merged block whose vertex mesh vertex v is, or kNoLeaf (a cell's own vertex, a face
    // or crossing vertex).
    uint32_t leafOf(uint32_t v) const { return v < vertexLeaf_.size() ? vertexLeaf_[v] : kNoLeaf; }

    uint32_t addVertex(const Vec3& p, const Vec3& n) {
        mesh_.positions.push_back(p);
        mesh_.normals.push_back(n);
        return uint32_t(mesh_.positions.size() - 1);
    }

    EdgeSample sample(int axis, const Node3& node, uint64_t& missing) const;

    // The triangles, outward (ring order when in0, else reversed), of the ring fanned from
    // center (apex < 0) or from ring[apex] (its two ring sides then left out), in ring order:
    // f(p, q, r) for each, until it returns false. Returns whether none did.
    template <class F>
    static bool forEachFanTriangle(bool in0, uint32_t center, const uint32_t* ring, int count,
                                   int apex, F&& f) {
        const uint32_t from = apex >= 0 ? ring[apex] : center;
        for (int t = 0; t < count; ++t) {
            const int next = (t + 1) % count;
            if (apex >= 0 && (t == apex || next == apex)) continue;
            uint32_t p = ring[t], q = ring[next];
            if (!in0) std::swap(p, q);
            if (!f(from, p, q)) return false;
        }
        return true;
    }

    // ---- The uniform contour (DualContour.cpp) ----
    void startRound();
    void collectActiveCells();
    void placeSheetVertices();
    template <class First>
    uint64_t placeAllSheetVertices(Vec3* out, Vec3* safe, First first) const;
    void placeSheetVerticesOf(uint64_t index, uint64_t& missing, Vec3* out, Vec3* safe) const;
    void unfoldSheetVertices();
    uint32_t sheetVertex(const Node3& cell, int localEdge);
    void fansOfCell(uint64_t index);
    void finishNormals();

    // ---- The octree: blocks of 2^k cells per axis merged into one vertex (OctreeMerge.cpp) ----
    bool insideOrPast(int i, int j, int k) const;
    bool blockTopologyOk(const Node3& lo, int size) const;
    bool blockSamples(const Node3& lo, int size, const uint32_t* first, const uint32_t* last,
                      std::vector<EdgeSample>& out) const;
    bool flatVertex(const Node3& lo, int size, const std::vector<EdgeSample>& samples, Vec3& vertex,
                    Vec3& normal) const;
    uint64_t blockKey(const Node3& lo, int level) const;
    void addLeaf(const BlockState& block, const Node3& lo, int level, const uint32_t* first,
                 const uint32_t* last, TopBlockWork& work);
    BlockState mergeBlock(const Node3& lo, int level, uint32_t* first, uint32_t* last,
                          TopBlockWork& work, bool inForbiddenTree);
    void mergeFlatBlocks();
    bool fits(uint32_t a, uint32_t b, uint32_t c, const Vec3& n) const;
    int chooseApex(const EdgeSample& s, bool in0, uint32_t center, const uint32_t* ring, int count);
    void noteNonManifoldLeaves();
    void noteFoldedLeaves();
    void dropUnusedVertices();

    // ---- The vertices on cell faces (FaceVertices.cpp) ----
    uint32_t& faceSlot(const Node3& faceMin, int g, int segment);
    bool bendsTowardCorner(const Vec3& x, const Vec3& p0, const Vec3& p1, const Node3& n0, int a0,
                           const Node3& n1, int a1, int u, int v) const;
    uint32_t faceVertex(int a, const Node3& n0, int g, int h, int dh);

    const HermiteGrid& grid_;
    const GridSpec& spec_;
    DualContourStats& stats_;
    const int workers_;
    double flatTolerance_;  // 0 after too many rounds: the uniform contour
    TriangleMesh mesh_;
    // The octree (mergeFlatBlocks): per entry of active_, its merged block or kNoLeaf (empty
    // when the octree is off); the merged blocks.
    std::vector<uint32_t> leafOfActive_;
    std::vector<Leaf> leaves_;
    std::vector<uint32_t> vertexLeaf_;    // per sheet vertex, its merged block or kNoLeaf
    std::vector<uint32_t> foldedLeaves_;  // merged blocks of rings no fan fits
    // The top blocks of mergeFlatBlocks, kept across rounds: the active cells (positions in
    // active_) by top block, each top block's first entry and key, its leaves, whether it must
    // be merged again, and per active cell its leaf within its top block.
    std::vector<uint32_t> topOrder_;
    std::vector<size_t> topStarts_;
    std::vector<uint64_t> topKeys_;
    std::vector<TopBlockWork> topWork_;
    std::vector<uint8_t> dirtyTop_;
    std::vector<uint32_t> localLeaf_;
    // Every active cell's own sheet vertices (placeSheetVertices, octree rounds): the first of
    // active cell i is finePlaced_[fineStart_[i]]; fineMissing_ counts their missing crossings.
    std::vector<uint32_t> fineStart_;
    std::vector<Vec3> finePlaced_;
    std::vector<Vec3> fineSafe_;  // their safe points (the mass points of their crossings)
    // Per sheet vertex, the mass point of its crossings (unfoldSheetVertices).
    std::vector<Vec3> safe_;
    uint64_t fineMissing_ = 0;
    // blockKeys that may not merge, nor any block inside them.
    std::unordered_set<uint64_t> forbidden_;
    std::vector<uint8_t> touched_;  // per vertex: a corner of a ring with a merged block
    std::vector<uint64_t> active_;
    std::vector<uint32_t> sheetBase_;  // per cell index: its first sheet vertex
    struct FaceLayer {
        int z = -1;
        std::vector<uint32_t> slots;    // per (i, j, axis, segment): see faceSlot
        std::vector<uint32_t> written;  // slots set since the layer was last reset
    };
    std::array<FaceLayer, 2> faceLayers_;
};

}  // namespace csg::detail
