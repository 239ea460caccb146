#include "csg/mesh/UnfoldVertices.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "csg/mesh/MeshCheck.h"
#include "primitives/base/Bounds.h"
#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

constexpr uint32_t kNoGroup = UINT32_MAX;

class Unfolder {
public:
    // Per worker: a group's triangles, as tested, and their boxes (grown by the tolerance).
    struct Scratch {
        std::vector<uint32_t> tris;
        std::vector<ContactTriangle> made;
        std::vector<Bounds3> boxes;
        uint64_t pairwise = 0;  // groups tested pair by pair
    };

    // Reads mesh; only run moves its vertices.
    Unfolder(const TriangleMesh& mesh, const std::vector<UnfoldGroup>& groups, double tol,
             int threads)
        : mesh_(mesh),
          groups_(groups),
          depthTol_(tol / tol::kUnfoldCheckMargin),
          flatTol_(tol * tol::kUnfoldCheckMargin),
          workers_(resolveThreads(threads)) {
        buildStars();
    }

    // Every group whose stars fold, checked on all workers, in group order.
    std::vector<uint32_t> foldedGroups() {
        std::vector<uint8_t> folded(groups_.size(), 0);
        std::vector<Scratch> scratch(static_cast<size_t>(workers_));
        constexpr uint64_t kChunk = 256;
        parallelFor((groups_.size() + kChunk - 1) / kChunk, workers_, [&](int w, uint64_t chunk) {
            const size_t end = std::min<size_t>(groups_.size(), (chunk + 1) * kChunk);
            for (size_t g = chunk * kChunk; g < end; ++g)
                folded[g] = folds(groups_[g], scratch[size_t(w)]);
        });
        stats_.checkedGroups += groups_.size();
        for (const Scratch& w : scratch) stats_.pairwiseGroups += w.pairwise;
        std::vector<uint32_t> pending;
        for (size_t g = 0; g < groups_.size(); ++g)
            if (folded[g]) pending.push_back(uint32_t(g));
        return pending;
    }

    // Moves the folded groups' vertices in positions, which are the mesh's own (the checks
    // read them through mesh_), toward safe (see unfoldVertices).
    UnfoldStats run(std::vector<Vec3>& positions, const std::vector<Vec3>& safe) {
        std::vector<uint32_t> pending = foldedGroups();
        // Each round: move the folded groups, then check the groups around the moved vertices.
        Scratch buffer;
        std::vector<uint8_t> stuck(groups_.size(), 0);
        for (int round = 0; round < kUnfoldRounds && !pending.empty(); ++round) {
            std::vector<uint32_t> around;
            for (const uint32_t g : pending) {
                ++stats_.foldedGroups;
                if (unfold(groups_[g], positions, safe, buffer)) {
                    ++stats_.movedGroups;
                } else {
                    ++stats_.unresolvedGroups;
                    stats_.unresolved.push_back(g);
                    stuck[g] = 1;  // at its safe points: moving it again changes nothing
                }
                groupsAround(groups_[g], around);
            }
            std::sort(around.begin(), around.end());
            around.erase(std::unique(around.begin(), around.end()), around.end());
            pending.clear();
            buffer.pairwise = 0;
            for (const uint32_t g : around) {
                if (stuck[g]) continue;
                ++stats_.checkedGroups;
                if (folds(groups_[g], buffer)) pending.push_back(g);
            }
            stats_.pairwiseGroups += buffer.pairwise;
        }
        stats_.leftFoldedGroups = pending.size();
        std::sort(stats_.unresolved.begin(), stats_.unresolved.end());
        return stats_;
    }

private:
    // Per vertex, the triangles using it, and per vertex its group.
    void buildStars() {
        const size_t n = mesh_.positions.size();
        Grouped<uint32_t> stars = trianglesByVertex(mesh_);
        starStart_ = std::move(stars.start);
        star_ = std::move(stars.values);
        groupOf_.assign(n, kNoGroup);
        for (size_t g = 0; g < groups_.size(); ++g)
            for (uint32_t k = 0; k < groups_[g].count; ++k)
                groupOf_[groups_[g].first + k] = uint32_t(g);
    }

    // A certificate that no two triangles around vertex v meet other than along what they
    // share: seen along the mean of their normals, each of them turns the same way around v
    // and their angles at v add up to one full turn, so their projections tile a disk around
    // v once and do not overlap (nor do the triangles, which project one-to-one). Cheap (no
    // pair of triangles is tested): most vertices pass, and only the rest are tested pairwise.
    // The pair test has tolerances the certificate does not: two neighbours folded onto each
    // other to within the coplanarity tolerance overlap by its rules although they are apart
    // (csg_grid at T = 0.013: a vertex clamped 1e-3 h inside a cell face, a sliver of its fan
    // folded 8 degrees from its neighbour, both seen edge-on along the mean). So neighbours
    // (triangles sharing an edge at v) must also face within 90 degrees of each other: then
    // their third corners lie on either side of the shared edge in either one's plane, where
    // the pair test finds them apart too.
    bool starIsEmbedded(uint32_t v) const {
        const Vec3 at = mesh_.positions[v];
        Vec3 mean(0.0);
        for (uint32_t i = starStart_[v]; i < starStart_[v + 1]; ++i) {
            const auto& tri = mesh_.triangles[star_[i]];
            mean += glm::cross(mesh_.positions[tri[1]] - mesh_.positions[tri[0]],
                               mesh_.positions[tri[2]] - mesh_.positions[tri[0]]);
        }
        const double len = glm::length(mean);
        if (!(len > 0.0)) return false;
        const Vec3 d = mean / len;
        double turn = 0.0;
        // Per triangle: the corners after v in its winding, and its normal (unnormalized).
        constexpr uint32_t kMaxStar = 32;
        const uint32_t count = starStart_[v + 1] - starStart_[v];
        if (count > kMaxStar) return false;
        uint32_t next[kMaxStar], prev[kMaxStar];
        Vec3 normal[kMaxStar];
        for (uint32_t i = 0; i < count; ++i) {
            const auto& tri = mesh_.triangles[star_[starStart_[v] + i]];
            const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
            next[i] = tri[size_t((k + 1) % 3)];
            prev[i] = tri[size_t((k + 2) % 3)];
            const Vec3 b = mesh_.positions[next[i]] - at;
            const Vec3 c = mesh_.positions[prev[i]] - at;
            normal[i] = glm::cross(b, c);
            const double sine = glm::dot(normal[i], d);
            if (!(sine > 0.0)) return false;
            turn += std::atan2(sine, glm::dot(b, c) - glm::dot(b, d) * glm::dot(c, d));
        }
        if (!(std::abs(turn - 2.0 * std::numbers::pi) < tol::kFullTurnSlack)) return false;
        // Neighbour j of i follows it around v: it shares the edge from v to i's last corner.
        for (uint32_t i = 0; i < count; ++i)
            for (uint32_t j = 0; j < count; ++j)
                if (next[j] == prev[i] && !(glm::dot(normal[i], normal[j]) > 0.0)) return false;
        return true;
    }

    // Whether a triangle of the group's stars crosses or overlaps another of them or, when
    // wide, any triangle sharing a corner with them (a move changes the group's triangles
    // only, but those may then fold onto a neighbour's that holds none of the group's
    // vertices). scratch is per worker.
    bool folds(const UnfoldGroup& group, Scratch& scratch, bool wide = false) const {
        if (!wide && group.count == 1 && starIsEmbedded(group.first)) return false;
        ++scratch.pairwise;
        std::vector<uint32_t>& tris = scratch.tris;
        tris.clear();
        for (uint32_t v = group.first; v < group.first + group.count; ++v)
            for (uint32_t i = starStart_[v]; i < starStart_[v + 1]; ++i) tris.push_back(star_[i]);
        std::sort(tris.begin(), tris.end());
        tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
        const size_t own = tris.size();
        if (wide) {
            for (size_t i = 0; i < own; ++i)
                for (const uint32_t corner : mesh_.triangles[tris[i]])
                    for (uint32_t k = starStart_[corner]; k < starStart_[corner + 1]; ++k)
                        tris.push_back(star_[k]);
            std::sort(tris.begin() + std::ptrdiff_t(own), tris.end());
            tris.erase(std::unique(tris.begin() + std::ptrdiff_t(own), tris.end()), tris.end());
            // Drop the group's own triangles from the neighbours' (both lists are sorted).
            const auto mine = tris.begin() + std::ptrdiff_t(own);
            tris.erase(std::remove_if(
                           mine, tris.end(),
                           [&](uint32_t t) { return std::binary_search(tris.begin(), mine, t); }),
                       tris.end());
        }
        scratch.made.clear();
        scratch.boxes.clear();
        for (const uint32_t t : tris) {
            const auto& tri = mesh_.triangles[t];
            const Vec3 &p0 = mesh_.positions[tri[0]], &p1 = mesh_.positions[tri[1]],
                       &p2 = mesh_.positions[tri[2]];
            scratch.made.push_back(contactTriangle(p0, p1, p2, depthTol_));
            Bounds3 box;
            box.extend(p0);
            box.extend(p1);
            box.extend(p2);
            box.lo -= Vec3(flatTol_);
            box.hi += Vec3(flatTol_);
            scratch.boxes.push_back(box);
        }
        for (size_t i = 0; i < own; ++i)
            for (size_t j = i + 1; j < tris.size(); ++j) {
                if (overlap(scratch.boxes[i], scratch.boxes[j]).empty()) continue;
                if (triangleContact(scratch.made[i], scratch.made[j], depthTol_, flatTol_) !=
                    TriangleContact::None)
                    return true;
            }
        return false;
    }

    // Moves a folded group toward its safe points (see unfoldVertices); whether it ends clean.
    bool unfold(const UnfoldGroup& group, std::vector<Vec3>& positions,
                const std::vector<Vec3>& safe, Scratch& scratch) {
        Vec3 from[4];
        const uint32_t count = std::min<uint32_t>(group.count, 4);
        for (uint32_t k = 0; k < count; ++k) from[k] = positions[group.first + k];
        auto place = [&](double t) {
            for (uint32_t k = 0; k < count; ++k)
                positions[group.first + k] = from[k] + t * (safe[group.first + k] - from[k]);
        };
        place(1.0);
        if (folds(group, scratch, true)) return false;
        double lo = 0.0, hi = 1.0;  // folded at lo, clean at hi
        for (int step = 0; step < kUnfoldBisections; ++step) {
            const double mid = 0.5 * (lo + hi);
            place(mid);
            (folds(group, scratch, true) ? lo : hi) = mid;
        }
        place(hi);
        return true;
    }

    // Appends the groups of every vertex sharing a triangle with the group's vertices.
    void groupsAround(const UnfoldGroup& group, std::vector<uint32_t>& out) const {
        for (uint32_t v = group.first; v < group.first + group.count; ++v)
            for (uint32_t i = starStart_[v]; i < starStart_[v + 1]; ++i)
                for (const uint32_t corner : mesh_.triangles[star_[i]])
                    if (groupOf_[corner] != kNoGroup) out.push_back(groupOf_[corner]);
    }

    const TriangleMesh& mesh_;
    const std::vector<UnfoldGroup>& groups_;
    // The contact tolerance of the check, divided and multiplied by tol::kUnfoldCheckMargin.
    const double depthTol_, flatTol_;
    const int workers_;
    UnfoldStats stats_;
    std::vector<uint32_t> starStart_, star_, groupOf_;
};

}  // namespace

std::vector<uint32_t> findFoldedGroups(const TriangleMesh& mesh,
                                       const std::vector<UnfoldGroup>& groups, double tol,
                                       int threads) {
    if (groups.empty() || mesh.triangles.empty()) return {};
    return Unfolder(mesh, groups, tol, threads).foldedGroups();
}

UnfoldStats unfoldVertices(TriangleMesh& mesh, const std::vector<UnfoldGroup>& groups,
                           const std::vector<Vec3>& safe, double tol, int threads) {
    if (groups.empty() || mesh.triangles.empty()) return {};
    return Unfolder(mesh, groups, tol, threads).run(mesh.positions, safe);
}

}  // namespace csg
