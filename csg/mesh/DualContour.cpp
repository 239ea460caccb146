// The uniform contour, Contourer's main part (Contourer.h): the active cells, one QEF vertex per
// sheet of each, the fan of each crossed edge, the unfolding of folded cells and the normals,
// and run(), which makes rounds of them (with the octree's merge and checks between).
#include "csg/mesh/DualContour.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "csg/mesh/CellTopology.h"
#include "csg/mesh/Contourer.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/Qef.h"
#include "csg/mesh/UnfoldVertices.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg::detail {

TriangleMesh Contourer::run() {
    collectActiveCells();
    // With the octree, a round with a ring no fan fits at a merged block (chooseApex), a
    // vertex whose triangles are not one disk (noteNonManifoldLeaves), a block vertex whose
    // triangles cross or overlap (noteFoldedLeaves) or a cell that stays folded next to
    // blocks (unfoldSheetVertices) forbids the blocks there and runs again. After
    // kOctreeMaxRounds the uniform contour is used.
    for (int round = 0;; ++round) {
        startRound();
        if (flatTolerance_ > 0.0) mergeFlatBlocks();
        placeSheetVertices();
        for (const uint64_t cell : active_) fansOfCell(cell);
        unfoldSheetVertices();
        if (!leaves_.empty()) {
            noteNonManifoldLeaves();
            noteFoldedLeaves();
        }
        if (foldedLeaves_.empty()) break;
        if (round + 1 >= kOctreeMaxRounds) {
            flatTolerance_ = 0.0;
            stats_.octreeFallback = true;
            continue;
        }
        // Forbid each such block and every block inside it (its cells keep their own
        // vertices). Forbidding only the block let its children fold in turn: on csg_grid3
        // (T = 0.028) 3556 blocks folded in the first round, then 701, 19, 4, 1, where this
        // rule gives 3556, 60, 19, 5, 3 (the tail is neighbours that fold once a block next
        // to them splits; each round costs about as much as the first).
        for (const uint32_t leaf : foldedLeaves_) {
            forbidden_.insert(leaves_[leaf].key);
            dirtyTop_[leaves_[leaf].top] = 1;
        }
    }
    if (!leaves_.empty()) dropUnusedVertices();
    finishNormals();
    return std::move(mesh_);
}

// Resets what one round of vertices and fans built (the active cells stay).
void Contourer::startRound() {
    mesh_ = {};
    leafOfActive_.clear();
    leaves_.clear();
    vertexLeaf_.clear();
    foldedLeaves_.clear();
    touched_.clear();
    faceLayers_ = {};
    stats_.sheetVertices = stats_.faceVertices = stats_.missingCrossings = 0;
    stats_.octreeLeaves = stats_.octreeCells = 0;
    ++stats_.octreeRounds;
}

// missing counts the sign changes without a crossing (DualContourStats::missingCrossings).
EdgeSample Contourer::sample(int axis, const Node3& node, uint64_t& missing) const {
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
    s.point = 0.5 * (spec_.node(node[0], node[1], node[2]) + spec_.node(next[0], next[1], next[2]));
    s.normal = Vec3(0.0);
    s.normal[axis] = inside(node) ? 1.0 : -1.0;
    s.measured = false;
    return s;
}

// Step 1: the cells with corners of both signs, in index order (deterministic output):
// each layer of cells on a worker, the layers joined in order.
void Contourer::collectActiveCells() {
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
void Contourer::placeSheetVertices() {
    // Indexed by cell: only active cells' entries are ever written or read.
    sheetBase_.resize(spec_.nodeCount());
    uint32_t next = 0;
    // A merged block's one vertex is numbered where its first cell comes.
    std::vector<uint32_t> leafVertex(leaves_.size(), kNone);
    for (size_t i = 0; i < active_.size(); ++i) {
        const uint64_t index = active_[i];
        const uint32_t leaf = leafOfActive_.empty() ? kNoLeaf : leafOfActive_[i];
        if (leaf != kNoLeaf) {
            if (leafVertex[leaf] == kNone) leafVertex[leaf] = next++;
            sheetBase_[index] = leafVertex[leaf];
            continue;
        }
        sheetBase_[index] = next;
        next += uint32_t(cellCycles(cellMask(cellNode(index))).count);
    }
    mesh_.positions.resize(next);
    mesh_.normals.assign(next, Vec3(0.0));
    if (!leaves_.empty()) vertexLeaf_.assign(next, kNoLeaf);
    for (size_t leaf = 0; leaf < leaves_.size(); ++leaf) {
        mesh_.positions[leafVertex[leaf]] = leaves_[leaf].vertex;
        vertexLeaf_[leafVertex[leaf]] = uint32_t(leaf);
    }
    stats_.sheetVertices = next;
    if (leafOfActive_.empty()) {
        safe_.resize(next);
        stats_.missingCrossings += placeAllSheetVertices(
            mesh_.positions.data(), safe_.data(), [&](size_t i) { return sheetBase_[active_[i]]; });
        return;
    }
    // With the octree, every cell's vertices are placed once (the first round) and copied
    // in each round for the cells outside merged blocks.
    if (fineStart_.empty()) {
        fineStart_.resize(active_.size() + 1, 0);
        for (size_t i = 0; i < active_.size(); ++i)
            fineStart_[i + 1] =
                fineStart_[i] + uint32_t(cellCycles(cellMask(cellNode(active_[i]))).count);
        finePlaced_.resize(fineStart_.back());
        fineSafe_.resize(fineStart_.back());
        fineMissing_ = placeAllSheetVertices(finePlaced_.data(), fineSafe_.data(),
                                             [&](size_t i) { return fineStart_[i]; });
    }
    stats_.missingCrossings += fineMissing_;
    safe_.resize(next);
    for (size_t i = 0; i < active_.size(); ++i)
        if (leafOfActive_[i] == kNoLeaf) {
            std::copy(finePlaced_.begin() + fineStart_[i], finePlaced_.begin() + fineStart_[i + 1],
                      mesh_.positions.begin() + sheetBase_[active_[i]]);
            std::copy(fineSafe_.begin() + fineStart_[i], fineSafe_.begin() + fineStart_[i + 1],
                      safe_.begin() + sheetBase_[active_[i]]);
        }
}

// The sheet vertices of every active cell i into out[first(i) ..) (its sheet count of them)
// and their safe points into safe[first(i) ..), on all workers in chunks; returns the count
// of missing crossings.
template <class First>
uint64_t Contourer::placeAllSheetVertices(Vec3* out, Vec3* safe, First first) const {
    std::vector<uint64_t> missing(size_t(workers_), 0);
    constexpr uint64_t kChunk = 1024;
    parallelFor((active_.size() + kChunk - 1) / kChunk, workers_, [&](int w, uint64_t chunk) {
        const size_t end = std::min<size_t>(active_.size(), (chunk + 1) * kChunk);
        for (size_t i = chunk * kChunk; i < end; ++i)
            placeSheetVerticesOf(active_[i], missing[size_t(w)], out + first(i), safe + first(i));
    });
    uint64_t total = 0;
    for (const uint64_t m : missing) total += m;
    return total;
}

// The sheet vertices of active cell index into out[0 .. its sheet count), and into
// safe[..] the mass points of their crossings (unfoldSheetVertices moves a vertex toward it).
void Contourer::placeSheetVerticesOf(uint64_t index, uint64_t& missing, Vec3* out,
                                     Vec3* safe) const {
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
        out[q] = placed[q];
        safe[q] = mass[q];
    }
}

// Step 5: the sheet vertices of each cell outside merged blocks, where triangles around
// them cross or overlap, moved toward the mass points of their crossings (UnfoldVertices.h).
void Contourer::unfoldSheetVertices() {
    std::vector<UnfoldGroup> groups;
    groups.reserve(active_.size());
    for (size_t i = 0; i < active_.size(); ++i) {
        if (!leafOfActive_.empty() && leafOfActive_[i] != kNoLeaf) continue;
        const uint64_t cell = active_[i];
        groups.push_back({sheetBase_[cell], uint32_t(cellCycles(cellMask(cellNode(cell))).count)});
    }
    const double tol = selfIntersectionTolerance(mesh_, tol::kSelfIntersectionContactRel);
    const UnfoldStats unfolded = unfoldVertices(mesh_, groups, safe_, tol, workers_);
    stats_.unfoldedCells = unfolded.movedGroups;
    stats_.unfoldFailures = unfolded.unresolvedGroups + unfolded.leftFoldedGroups;
    if (leaves_.empty() || unfolded.unresolved.empty()) return;
    // With the octree, a cell still folded at its mass points sits next to merged blocks
    // whose fans leave it no clean position: the blocks at its triangles are noted
    // (foldedLeaves_), so the next round does not merge them.
    std::vector<uint8_t> stuck(mesh_.positions.size(), 0);
    for (const uint32_t g : unfolded.unresolved)
        for (uint32_t k = 0; k < groups[g].count; ++k) stuck[groups[g].first + k] = 1;
    for (const auto& tri : mesh_.triangles) {
        if (!stuck[tri[0]] && !stuck[tri[1]] && !stuck[tri[2]]) continue;
        for (const uint32_t corner : tri)
            if (leafOf(corner) != kNoLeaf) foldedLeaves_.push_back(leafOf(corner));
    }
}

uint32_t Contourer::sheetVertex(const Node3& cell, int localEdge) {
    const uint32_t base = sheetBase_[cellIndex(cell)];
    return base + uint32_t(cellCycles(cellMask(cell)).edgeCycle[size_t(localEdge)]);
}

// Step 3: the fan of each crossed edge that starts at this cell's minimum corner.
void Contourer::fansOfCell(uint64_t index) {
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
        // Cells of one merged block share its vertex: it enters the ring once, with no face
        // vertex inside the block.
        static constexpr int kRing[4][2] = {{-1, -1}, {0, -1}, {0, 0}, {-1, 0}};
        uint32_t sheet[4];
        for (int q = 0; q < 4; ++q) {
            Node3 cell = n0;
            cell[b] += kRing[q][0];
            cell[c] += kRing[q][1];
            sheet[q] = sheetVertex(cell, 4 * a + (kRing[q][0] < 0) + 2 * (kRing[q][1] < 0));
        }
        uint32_t ring[8];
        int count = 0;
        for (int q = 0; q < 4; ++q) {
            if (count == 0 || ring[count - 1] != sheet[q]) ring[count++] = sheet[q];
            if (sheet[(q + 1) % 4] == sheet[q]) continue;
            const int* next = kRing[(q + 1) % 4];
            const bool differOnB = next[0] != kRing[q][0];
            const int g = differOnB ? b : c, h = differOnB ? c : b;
            const int dh = differOnB ? kRing[q][1] : kRing[q][0];
            const uint32_t f = faceVertex(a, n0, g, h, dh);
            if (f != kNone) ring[count++] = f;
        }
        if (count > 1 && ring[count - 1] == ring[0]) --count;
        // Two distinct vertices (an edge inside a block or a face between two blocks) would
        // make two opposite triangles on the same corners: no fan. No face vertex was added
        // then (one comes only between two distinct sheet vertices), so the crossing's
        // vertex is the last one.
        if (count <= 2) {
            mesh_.positions.pop_back();
            mesh_.normals.pop_back();
            continue;
        }

        // Outward is +a when the edge leaves the solid going up the axis. A ring with a
        // merged block's vertex may be fanned from one of its vertices instead (apex).
        const int apex = vertexLeaf_.empty() ? -1 : chooseApex(s, in0, center, ring, count);
        forEachFanTriangle(in0, center, ring, count, apex, [&](uint32_t p, uint32_t q, uint32_t r) {
            mesh_.triangles.push_back({p, q, r});
            mesh_.triangleMaterial.push_back(s.material);
            return true;
        });
    }
}

// Step 4: normals of QEF and face vertices from their triangles (area-weighted); crossing
// vertices keep the exact normal.
void Contourer::finishNormals() {
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

}  // namespace csg::detail

namespace csg {

TriangleMesh dualContour(const HermiteGrid& grid, DualContourStats* stats, int threads) {
    DualContourOptions options;
    options.threads = threads;
    return dualContour(grid, options, stats);
}

TriangleMesh dualContour(const HermiteGrid& grid, const DualContourOptions& options,
                         DualContourStats* stats) {
    DualContourStats local;
    DualContourStats& s = stats ? *stats : local;
    auto contour = [&](const DualContourOptions& o) {
        s = {};
        s.cells = grid.spec().cellCount();
        s.thinEdges = grid.thinEdges();
        s.thinAt = grid.thinAt();
        return detail::Contourer(grid, s, o).run();
    };
    TriangleMesh mesh = contour(options);
    // The safety net of the octree (DualContour.h): a merged mesh that is not a closed manifold
    // is replaced by the uniform one, which always is.
    if (options.flatTolerance > 0.0 && s.octreeLeaves > 0 &&
        !checkTopology(mesh).closedManifold()) {
        DualContourOptions uniform = options;
        uniform.flatTolerance = 0.0;
        mesh = contour(uniform);
        s.octreeFallback = true;
    }
    return mesh;
}

}  // namespace csg
