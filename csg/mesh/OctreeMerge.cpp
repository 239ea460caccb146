// The adaptive octree of Contourer (Contourer.h; DualContour.h describes it): blocks of up to
// 2^kOctreeMaxLevel cells per axis merged into one vertex where Ju's topology test and the
// flatness test pass, the vertex a ring with a merged block's vertex is fanned from, and the
// checks (non-manifold and folded blocks) whose blocks the next round does not merge.
#include <algorithm>
#include <array>
#include <cmath>
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

// The merged blocks whose vertex's triangles cross or overlap (a sliver folded flat onto a
// neighbour where a ring next to the block was fanned), noted in foldedLeaves_: the next
// round does not merge them (their vertices may not move as a cell's do, unfoldSheetVertices:
// the block's other triangles would move too).
void Contourer::noteFoldedLeaves() {
    std::vector<UnfoldGroup> groups;
    for (uint32_t v = 0; v < uint32_t(vertexLeaf_.size()); ++v)
        if (vertexLeaf_[v] != kNoLeaf) groups.push_back({v, 1});
    const double tol = selfIntersectionTolerance(mesh_, tol::kSelfIntersectionContactRel);
    for (const uint32_t g : findFoldedGroups(mesh_, groups, tol, workers_))
        foldedLeaves_.push_back(vertexLeaf_[groups[g].first]);
}

// A node's sign, outside past the grid's last node: a block may reach past the grid (top
// blocks are aligned to multiples of their size), and the grid's boundary nodes are all
// outside, so the cells past it are empty.
bool Contourer::insideOrPast(int i, int j, int k) const {
    if (i >= spec_.nodes[0] || j >= spec_.nodes[1] || k >= spec_.nodes[2]) return false;
    return grid_.inside(i, j, k);
}

// Ju's topology test on block [lo, lo + size] (nodes; size even): the corners give one sheet
// and no ambiguous face, and every mid-edge, mid-face and centre node agrees in sign with a
// corner of its edge, face or block. Applied at every level, each block edge then changes
// sign at most once along its nodes.
bool Contourer::blockTopologyOk(const Node3& lo, int size) const {
    const int half = size / 2;
    auto at = [&](int x, int y, int z) {
        return insideOrPast(lo[0] + x * half, lo[1] + y * half, lo[2] + z * half);
    };
    uint8_t mask = 0;
    for (int corner = 0; corner < 8; ++corner)
        if (at(2 * (corner & 1), 2 * ((corner >> 1) & 1), 2 * ((corner >> 2) & 1)))
            mask = uint8_t(mask | (1u << corner));
    const CellCycles& cycles = cellCycles(mask);
    if (cycles.count != 1 || cycles.ambiguousFace) return false;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x) {
                if (x != 1 && y != 1 && z != 1) continue;  // a corner
                const bool sign = at(x, y, z);
                bool agrees = false;
                // The corners of the smallest edge, face or block holding the node: each
                // middle coordinate runs over both ends.
                for (int corner = 0; corner < 8 && !agrees; ++corner) {
                    const int cx = corner & 1, cy = (corner >> 1) & 1, cz = (corner >> 2) & 1;
                    if ((x != 1 && cx) || (y != 1 && cy) || (z != 1 && cz)) continue;
                    agrees =
                        at(x == 1 ? 2 * cx : x, y == 1 ? 2 * cy : y, z == 1 ? 2 * cz : z) == sign;
                }
                if (!agrees) return false;
            }
    return true;
}

// The samples of the crossed edges of the block's cells [lo, lo + size), each edge once (by
// the cell whose minimum corner is the edge's start, clamped into the block: every cell
// around a crossed edge is active). False when one was not measured (a midpoint fallback).
bool Contourer::blockSamples(const Node3& lo, int size, const uint32_t* first, const uint32_t* last,
                             std::vector<EdgeSample>& out) const {
    out.clear();
    uint64_t missing = 0;
    for (const uint32_t* p = first; p != last; ++p) {
        const Node3 cell = cellNode(active_[*p]);
        const CellCycles& cycles = cellCycles(cellMask(cell));
        for (int e = 0; e < 12; ++e) {
            if (cycles.edgeCycle[size_t(e)] < 0) continue;
            const int a = e / 4, b = (a + 1) % 3, c = (a + 2) % 3;
            const int ob = e & 1, oc = (e >> 1) & 1;
            if ((ob && cell[b] != lo[b] + size - 1) || (oc && cell[c] != lo[c] + size - 1))
                continue;
            Node3 n = cell;
            n[b] += ob;
            n[c] += oc;
            out.push_back(sample(a, n, missing));
            if (!out.back().measured) return false;
        }
    }
    return true;
}

// The block's one vertex (the QEF of all its samples, clamped to the block inset a hair, as
// a cell's), when the block is flat: every normal within tol::kOctreeConeAngle of their
// mean and every tangent plane within flatTolerance_ of the vertex.
bool Contourer::flatVertex(const Node3& lo, int size, const std::vector<EdgeSample>& samples,
                           Vec3& vertex, Vec3& normal) const {
    Qef3 qef;
    Vec3 sum(0.0);
    for (const EdgeSample& s : samples) {
        qef.add(s.point, s.normal);
        sum += s.normal;
    }
    const double length = glm::length(sum);
    if (samples.empty() || !(length > 0.0)) return false;
    const Vec3 mean = sum / length;
    normal = mean;
    const double cone = std::cos(tol::kOctreeConeAngle);
    for (const EdgeSample& s : samples)
        if (glm::dot(s.normal, mean) < cone) return false;
    // The block's box, cut at the grid's last node (past it the block is empty).
    const Node3 hi{std::min(lo[0] + size, spec_.nodes[0] - 1),
                   std::min(lo[1] + size, spec_.nodes[1] - 1),
                   std::min(lo[2] + size, spec_.nodes[2] - 1)};
    const Vec3 lo3 = spec_.node(lo[0], lo[1], lo[2]), hi3 = spec_.node(hi[0], hi[1], hi[2]);
    const Vec3 extent = hi3 - lo3;
    const Vec3 inset(separation(std::min({extent.x, extent.y, extent.z})));
    const Bounds3 box{lo3 + inset, hi3 - inset};
    vertex = glm::clamp(qef.solve(box), box.lo, box.hi);
    for (const EdgeSample& s : samples)
        if (std::fabs(glm::dot(s.normal, vertex - s.point)) > flatTolerance_) return false;
    return true;
}

// A block's name across rounds: its first cell and its level.
uint64_t Contourer::blockKey(const Node3& lo, int level) const {
    return cellIndex(lo) * (kOctreeMaxLevel + 1) + uint64_t(level);
}

void Contourer::addLeaf(const BlockState& block, const Node3& lo, int level, const uint32_t* first,
                        const uint32_t* last, TopBlockWork& work) {
    for (const uint32_t* p = first; p != last; ++p) localLeaf_[*p] = uint32_t(work.leaves.size());
    work.leaves.push_back({block.vertex, block.normal, blockKey(lo, level)});
}

// Block of 2^level cells per axis at lo whose active cells (positions in active_) are
// [first, last): merges bottom-up; the mergeable children of a block that does not merge
// become leaves (fine cells, level 0, keep their own vertices). inForbiddenTree: this
// block or one around it is in forbidden_.
Contourer::BlockState Contourer::mergeBlock(const Node3& lo, int level, uint32_t* first,
                                            uint32_t* last, TopBlockWork& work,
                                            bool inForbiddenTree) {
    if (level == 0) {
        if (first == last) return {true, false, Vec3(0.0)};
        const CellCycles& cycles = cellCycles(cellMask(cellNode(active_[*first])));
        return {cycles.count == 1 && !cycles.ambiguousFace, true, Vec3(0.0)};
    }
    const int half = 1 << (level - 1), size = 2 * half;
    inForbiddenTree =
        inForbiddenTree || (!forbidden_.empty() && forbidden_.count(blockKey(lo, level)));
    // Split the cells into the 8 children (octant bit a: the cell is in the upper half on
    // axis a), in order z, y, x so each child's cells are contiguous: on axis a, each run
    // [bounds[o], bounds[o + 2 step]) splits at bounds[o + step], step = 2^a.
    uint32_t* bounds[9];
    bounds[0] = first;
    bounds[8] = last;
    for (int a = 2; a >= 0; --a) {
        const int step = 1 << a;
        for (int o = 0; o < 8; o += 2 * step)
            bounds[o + step] = std::partition(bounds[o], bounds[o + 2 * step], [&](uint32_t p) {
                return cellNode(active_[p])[a] < lo[a] + half;
            });
    }
    BlockState child[8];
    Node3 childLo[8];
    bool all = true, surface = false;
    for (int o = 0; o < 8; ++o) {
        childLo[o] = {lo[0] + half * (o & 1), lo[1] + half * ((o >> 1) & 1),
                      lo[2] + half * ((o >> 2) & 1)};
        child[o] =
            mergeBlock(childLo[o], level - 1, bounds[o], bounds[o + 1], work, inForbiddenTree);
        all = all && child[o].mergeable;
        surface = surface || child[o].surface;
    }
    BlockState self{all, surface, Vec3(0.0)};
    if (inForbiddenTree) self.mergeable = false;
    if (self.mergeable && surface)
        self.mergeable = blockTopologyOk(lo, size) &&
                         blockSamples(lo, size, first, last, work.samples) &&
                         flatVertex(lo, size, work.samples, self.vertex, self.normal);
    if (!self.mergeable && level > 1)
        for (int o = 0; o < 8; ++o)
            if (child[o].mergeable && child[o].surface)
                addLeaf(child[o], childLo[o], level - 1, bounds[o], bounds[o + 1], work);
    return self;
}

// Step 1b: the octree over top blocks of 2^kOctreeMaxLevel cells, each on one worker; the
// leaves are numbered in top-block order, so the result is the same for any thread count.
void Contourer::mergeFlatBlocks() {
    constexpr int kTop = 1 << kOctreeMaxLevel;
    std::array<uint64_t, 3> tops;
    for (int a = 0; a < 3; ++a) tops[size_t(a)] = uint64_t(spec_.nodes[a] - 1 + kTop - 1) / kTop;
    // The first round sorts the active cells into top blocks; later rounds merge again only
    // the top blocks where a block was forbidden (dirtyTop_), the others keep their leaves.
    if (topStarts_.empty()) {
        std::vector<std::pair<uint64_t, uint32_t>> keyed(active_.size());
        for (size_t i = 0; i < active_.size(); ++i) {
            const Node3 c = cellNode(active_[i]);
            keyed[i] = {uint64_t(c[0] / kTop) +
                            tops[0] * (uint64_t(c[1] / kTop) + tops[1] * uint64_t(c[2] / kTop)),
                        uint32_t(i)};
        }
        std::sort(keyed.begin(), keyed.end());
        topOrder_.resize(keyed.size());
        for (size_t i = 0; i < keyed.size(); ++i) {
            if (i == 0 || keyed[i].first != keyed[i - 1].first) {
                topStarts_.push_back(i);
                topKeys_.push_back(keyed[i].first);
            }
            topOrder_[i] = keyed[i].second;
        }
        topStarts_.push_back(topOrder_.size());
        topWork_.resize(topKeys_.size());
        dirtyTop_.assign(topKeys_.size(), 1);
        localLeaf_.assign(active_.size(), kNoLeaf);
    }
    const size_t blocks = topKeys_.size();
    parallelFor(blocks, workers_, [&](int, uint64_t block) {
        if (!dirtyTop_[block]) return;
        uint32_t* first = topOrder_.data() + topStarts_[block];
        uint32_t* last = topOrder_.data() + topStarts_[block + 1];
        for (uint32_t* p = first; p != last; ++p) localLeaf_[*p] = kNoLeaf;
        const uint64_t key = topKeys_[block];
        const Node3 lo{int(key % tops[0]) * kTop, int((key / tops[0]) % tops[1]) * kTop,
                       int(key / (tops[0] * tops[1])) * kTop};
        TopBlockWork& w = topWork_[block];
        w = {};
        const BlockState top = mergeBlock(lo, kOctreeMaxLevel, first, last, w, false);
        if (top.mergeable && top.surface) addLeaf(top, lo, kOctreeMaxLevel, first, last, w);
        w.samples = {};
        dirtyTop_[block] = 0;
    });
    // Number the leaves globally: top blocks in order.
    leafOfActive_.assign(active_.size(), kNoLeaf);
    uint32_t offset = 0;
    for (size_t block = 0; block < blocks; ++block) {
        for (size_t i = topStarts_[block]; i < topStarts_[block + 1]; ++i) {
            const uint32_t p = topOrder_[i];
            if (localLeaf_[p] != kNoLeaf) {
                leafOfActive_[p] = localLeaf_[p] + offset;
                ++stats_.octreeCells;
            }
        }
        const TopBlockWork& w = topWork_[block];
        offset += uint32_t(w.leaves.size());
        for (Leaf leaf : w.leaves) {
            leaf.top = uint32_t(block);
            leaves_.push_back(leaf);
        }
    }
    stats_.octreeLeaves = leaves_.size();
}

// Whether triangle (a, b, c), outward, fits the surface whose exact normal near it is n:
// it faces along n, and where a merged block's vertex is a corner and n lies on that
// block's own smooth patch (within twice its normal cone of the block's mean normal), it
// turns from n by less than tol::kOctreeFanTurnCos. (A triangle from a crossing across a
// crease, a box edge next to a merged face, legitimately turns further.)
bool Contourer::fits(uint32_t a, uint32_t b, uint32_t c, const Vec3& n) const {
    const Vec3& pa = mesh_.positions[a];
    const Vec3 cross = glm::cross(mesh_.positions[b] - pa, mesh_.positions[c] - pa);
    const double facing = glm::dot(cross, n);
    if (!(facing > 0.0)) return false;
    const double sameSheet = std::cos(2.0 * tol::kOctreeConeAngle);
    for (const uint32_t v : {a, b, c}) {
        const uint32_t leaf = leafOf(v);
        if (leaf != kNoLeaf && glm::dot(n, leaves_[leaf].normal) >= sameSheet &&
            facing < tol::kOctreeFanTurnCos * glm::length(cross))
            return false;
    }
    return true;
}

// The vertex a ring with a merged block's vertex is fanned from: -1 for the crossing
// (center), as every other ring, when that fan fits the surface (fits); else the
// first ring vertex whose fan fits (the same boundary, so the mesh stays closed: a ring of
// three becomes Ju's one triangle). A block's vertex lies anywhere in its block, so seen
// from a crossing on the block's face it may lie past the ring's other vertices and the
// crossing's fan fold over. When no fan fits, the blocks of the ring are noted
// (foldedLeaves_: the next round does not merge them) and the crossing's fan is kept.
int Contourer::chooseApex(const EdgeSample& s, bool in0, uint32_t center, const uint32_t* ring,
                          int count) {
    bool merged = false;
    for (int t = 0; t < count; ++t) merged = merged || leafOf(ring[t]) != kNoLeaf;
    if (!merged) return -1;
    touched_.resize(mesh_.positions.size(), 0);
    touched_[center] = 1;
    for (int t = 0; t < count; ++t) touched_[ring[t]] = 1;
    if (!s.measured) return -1;
    for (int apex = -1; apex < count; ++apex)
        if (forEachFanTriangle(
                in0, center, ring, count, apex,
                [&](uint32_t p, uint32_t q, uint32_t r) { return fits(p, q, r, s.normal); }))
            return apex;
    for (int t = 0; t < count; ++t)
        if (leafOf(ring[t]) != kNoLeaf) foldedLeaves_.push_back(leafOf(ring[t]));
    return -1;
}

// The merged blocks at vertices of the mesh whose triangles do not form one disk around
// them (an edge used other than once each way, or two fans meeting at the vertex): merging
// changed the rings around them in a way Ju's test does not rule out (a block wrapping
// around a neighbour's face). The blocks among such a vertex and its triangles' corners are
// noted in foldedLeaves_. The uniform contour is a manifold, so only merging causes these.
void Contourer::noteNonManifoldLeaves() {
    const size_t n = mesh_.positions.size();
    const Grouped<uint32_t> byVertex = trianglesByVertex(mesh_);
    const std::vector<uint32_t>& start = byVertex.start;
    const std::vector<uint32_t>& around = byVertex.values;
    auto noteAt = [&](uint32_t v) {
        for (uint32_t i = start[v]; i < start[v + 1]; ++i)
            for (const uint32_t corner : mesh_.triangles[around[i]])
                if (leafOf(corner) != kNoLeaf) foldedLeaves_.push_back(leafOf(corner));
    };
    // Around a manifold vertex the far edges of its triangles (a -> b for triangle v, a, b)
    // form one cycle: every a starts one edge, and walking from any reaches all.
    std::vector<std::pair<uint32_t, uint32_t>> link;
    touched_.resize(n, 0);
    for (size_t v = 0; v < n; ++v) {
        if (!touched_[v]) continue;  // all its triangles are the uniform contour's
        link.clear();
        for (uint32_t i = start[v]; i < start[v + 1]; ++i) {
            const auto& tri = mesh_.triangles[around[i]];
            const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
            link.push_back({tri[size_t((k + 1) % 3)], tri[size_t((k + 2) % 3)]});
        }
        if (link.empty()) continue;
        std::sort(link.begin(), link.end());
        bool ok = true;
        for (size_t i = 1; i < link.size() && ok; ++i) ok = link[i].first != link[i - 1].first;
        size_t steps = 0;
        for (uint32_t at = link[0].second; ok && steps < link.size(); ++steps) {
            const auto next =
                std::lower_bound(link.begin(), link.end(), std::pair<uint32_t, uint32_t>{at, 0});
            if (next == link.end() || next->first != at)
                ok = false;
            else if (next == link.begin())
                break;  // back at the first edge
            else
                at = next->second;
        }
        if (!ok || steps + 1 != link.size()) noteAt(uint32_t(v));
    }
}

// With the octree, crossings whose ring was fanned from another vertex are left without a
// triangle: drop every vertex no triangle uses (the order of the rest is kept).
void Contourer::dropUnusedVertices() {
    std::vector<uint32_t> remap(mesh_.positions.size(), kNone);
    for (const auto& tri : mesh_.triangles)
        for (const uint32_t v : tri) remap[v] = 0;
    uint32_t next = 0;
    for (size_t v = 0; v < remap.size(); ++v) {
        if (remap[v] == kNone) continue;
        remap[v] = next;
        mesh_.positions[next] = mesh_.positions[v];
        mesh_.normals[next] = mesh_.normals[v];
        ++next;
    }
    mesh_.positions.resize(next);
    mesh_.normals.resize(next);
    for (auto& tri : mesh_.triangles)
        for (uint32_t& v : tri) v = remap[v];
}

}  // namespace csg::detail
