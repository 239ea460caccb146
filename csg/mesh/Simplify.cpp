#include "csg/mesh/Simplify.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <vector>

#include "csg/mesh/Decimate.h"
#include "csg/mesh/MeshCheck.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

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
// the whole mesh that follows. With crossings checked, a slab also sees the triangles of the
// slabs that can come near it (step 4). Returns the merged mesh as one piece, or nothing when
// a slab is not a 2-manifold with boundary (a vertex pinched at the slab's border). stats is
// added to.
std::optional<Piece> decimateInBlocks(const Piece& whole, const CollapseLimits& limits, int blocks,
                                      int threads, DecimateStats& stats) {
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

    // Step 3: the slabs as pieces (local vertex indices).
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
    // Step 4: the slabs decimated, in parallel. With crossings checked, a slab must also keep
    // clear of its neighbours' triangles, which it cannot see change: slabs whose triangles can
    // come near each other are decimated in different rounds, and each tests its collapses
    // against the near triangles of those others as they are then (unchanged during its round).
    // A triangle's corners are vertices of its slab, and a slab's vertices lie within `reach`
    // (the largest extent along the axis of a triangle of whole) of its keys: slabs i < j can
    // meet only where [cuts[j - 1] - reach, ...) comes within the contact margin of
    // (..., cuts[i] + reach], always for neighbours, rarely for others (a slab between them
    // thinner than 2 reach). Unchecked, every slab runs in the first round, with no obstacles.
    const bool checking = limits.contactTol > 0.0;
    double reach = 0.0;
    for (const auto& tri : whole.triangles) {
        const double a = whole.positions[tri[0]][axis], b = whole.positions[tri[1]][axis],
                     c = whole.positions[tri[2]][axis];
        reach = std::max(reach, std::max({a, b, c}) - std::min({a, b, c}));
    }
    const double margin = 2.0 * (limits.contactTol + limits.flatTol);
    auto lowest = [&](int b) { return b == 0 ? -INFINITY : cuts[size_t(b - 1)] - reach; };
    auto highest = [&](int b) { return b + 1 == blocks ? INFINITY : cuts[size_t(b)] + reach; };
    auto meet = [&](int i, int j) {  // i < j
        return j == i + 1 || lowest(j) <= highest(i) + margin;
    };
    std::vector<int> round(static_cast<size_t>(blocks), 0);
    int rounds = 1;
    if (checking)
        for (int b = 0; b < blocks; ++b) {
            // The first round no earlier slab that b meets runs in.
            std::vector<uint8_t> taken(static_cast<size_t>(blocks), 0);
            for (int i = 0; i < b; ++i)
                if (meet(i, b)) taken[size_t(round[size_t(i)])] = 1;
            while (taken[size_t(round[size_t(b)])]) ++round[size_t(b)];
            rounds = std::max(rounds, round[size_t(b)] + 1);
        }
    std::atomic<bool> refused{false};
    std::vector<DecimateStats> slabStats(static_cast<size_t>(blocks));
    for (int r = 0; r < rounds; ++r) {
        std::vector<uint32_t> now;
        for (int b = 0; b < blocks; ++b)
            if (round[size_t(b)] == r) now.push_back(uint32_t(b));
        parallelFor(now.size(), threads, [&](int, uint64_t k) {
            const int b = int(now[k]);
            CollapseLimits slabLimits = limits;
            if (checking) {
                const double from = lowest(b) - margin, to = highest(b) + margin;
                for (int j = 0; j < blocks; ++j) {
                    if (j == b || !meet(std::min(b, j), std::max(b, j))) continue;
                    const Piece& other = pieces[size_t(j)];
                    for (const auto& tri : other.triangles) {
                        const std::array<Vec3, 3> corners{other.positions[tri[0]],
                                                          other.positions[tri[1]],
                                                          other.positions[tri[2]]};
                        const double a = corners[0][axis], c = corners[1][axis],
                                     d = corners[2][axis];
                        if (std::max({a, c, d}) >= from && std::min({a, c, d}) <= to)
                            slabLimits.obstacles.push_back(corners);
                    }
                }
            }
            if (!decimate(pieces[size_t(b)], slabLimits, &slabStats[size_t(b)])) refused = true;
        });
    }
    if (refused) return std::nullopt;
    for (const DecimateStats& d : slabStats) {
        stats.collapses += d.collapses;
        stats.refusedCrossing += d.refusedCrossing;
    }

    // Step 5: the slabs merged into one piece, vertices indexed as in the input's order of
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
                      int threads, bool refuseCrossings) {
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

    // Step 2: decimate, a big mesh in blocks first (on all workers), then the whole. Crossings
    // are tested as findSelfIntersections would test the mesh, made stricter by the margin the
    // unfolding uses, so that the result passes that test also after rounding to float.
    CollapseLimits limits;
    limits.maxDeviation = maxDeviation;
    if (refuseCrossings) {
        const double contact = selfIntersectionTolerance(mesh, tol::kSelfIntersectionContactRel);
        limits.contactTol = contact / tol::kUnfoldCheckMargin;
        limits.flatTol = contact * tol::kUnfoldCheckMargin;
    }
    DecimateStats counts;
    const int blocks = int(std::min(kMaxBlocks, nt / kTrianglesPerBlock));
    Piece piece;
    if (blocks >= 2) {
        if (std::optional<Piece> merged =
                decimateInBlocks(whole, limits, blocks, threads, counts)) {
            piece = std::move(*merged);
            s.blocks = blocks;
            s.trianglesAfterBlocks = piece.triangles.size();
        }
        s.blocksSeconds = since(phase);
    }
    if (piece.triangles.empty()) piece = std::move(whole);
    // Not manifold: left to the checks downstream.
    if (!decimate(piece, limits, &counts)) return mesh;
    s.built = true;
    s.collapses = counts.collapses;
    s.refusedCrossing = counts.refusedCrossing;
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
