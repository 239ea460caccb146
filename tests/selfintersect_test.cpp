// findSelfIntersections (csg/mesh/MeshCheck.h) on hand-made triangle pairs and closed meshes,
// each with a count known by construction; unfoldVertices (csg/mesh/UnfoldVertices.h) on a
// hand-folded one.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/UnfoldVertices.h"

namespace csg {
namespace {

TriangleMesh pair(std::array<Vec3, 3> a, std::array<Vec3, 3> b) {
    TriangleMesh m;
    for (const Vec3& p : a) m.positions.push_back(p);
    for (const Vec3& p : b) m.positions.push_back(p);
    m.triangles = {{0, 1, 2}, {3, 4, 5}};
    return m;
}

// An axis-aligned cube [0, 1]^3, two triangles a face, oriented outward.
TriangleMesh cube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

TEST(SelfIntersections, CrossingPairCountsOnce) {
    // One triangle in z = 0, the other standing through it along x = 0.2.
    const TriangleMesh m = pair({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
                                {Vec3(0.2, 0, -1), Vec3(0.2, 0.3, 1), Vec3(0.2, -0.3, 1)});
    const SelfIntersections s = findSelfIntersections(m);
    EXPECT_EQ(s.pairs, 1u);
    EXPECT_EQ(s.coplanarPairs, 0u);
    EXPECT_EQ(s.exampleA, 0u);
    EXPECT_EQ(s.exampleB, 1u);
    EXPECT_NEAR(s.example.x, 0.2, 1e-12);
    EXPECT_NEAR(s.example.z, 0.0, 1e-12);
}

TEST(SelfIntersections, SamePairApartIsClean) {
    const TriangleMesh m = pair({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
                                {Vec3(5.2, 0, -1), Vec3(5.2, 0.3, 1), Vec3(5.2, -0.3, 1)});
    EXPECT_EQ(findSelfIntersections(m).pairs, 0u);
    // Lifted just above the plane: its box overlaps, the triangles do not.
    const TriangleMesh above = pair({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
                                    {Vec3(0.2, 0, 0.01), Vec3(0.2, 0.3, 1), Vec3(0.2, -0.3, 1)});
    EXPECT_EQ(findSelfIntersections(above).pairs, 0u);
}

TEST(SelfIntersections, ClosedMeshesAreClean) {
    TriangleMesh tet;
    tet.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    ASSERT_TRUE(checkTopology(tet).closedManifold());
    EXPECT_EQ(findSelfIntersections(tet).pairs, 0u);
    const TriangleMesh c = cube();
    ASSERT_TRUE(checkTopology(c).closedManifold());
    EXPECT_EQ(findSelfIntersections(c).pairs, 0u);
}

TEST(SelfIntersections, SharedVertexPiercingCounts) {
    // Both share the origin; the second's far edge passes through the first's interior.
    const Vec3 o(0, 0, 0);
    const TriangleMesh pierce =
        pair({o, Vec3(2, 0, 0), Vec3(0, 2, 0)}, {o, Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1)});
    EXPECT_EQ(findSelfIntersections(pierce).pairs, 1u);
    // Same shared vertex, the far edge beside the first triangle: they touch at o only.
    TriangleMesh touch =
        pair({o, Vec3(2, 0, 0), Vec3(0, 2, 0)}, {o, Vec3(-0.5, -0.5, -1), Vec3(-0.5, -0.5, 1)});
    EXPECT_EQ(findSelfIntersections(touch).pairs, 0u);
    // Shared by index rather than by a repeated position: the same verdicts.
    touch.positions.resize(5);
    touch.positions[3] = Vec3(-0.5, -0.5, -1);
    touch.positions[4] = Vec3(-0.5, -0.5, 1);
    touch.triangles = {{0, 1, 2}, {0, 3, 4}};
    EXPECT_EQ(findSelfIntersections(touch).pairs, 0u);
}

TEST(SelfIntersections, SharedEdgeFoldedFlatCounts) {
    const Vec3 p(0, 0, 0), q(1, 0, 0);
    // The second triangle folded onto the first (its third corner on the same side of pq).
    const SelfIntersections folded =
        findSelfIntersections(pair({p, q, Vec3(0.5, 1, 0)}, {q, p, Vec3(0.3, 0.5, 0)}));
    EXPECT_EQ(folded.pairs, 1u);
    EXPECT_EQ(folded.coplanarPairs, 1u);
    // Unfolded (a flat neighbour) and bent (a ridge): they meet along pq only.
    EXPECT_EQ(
        findSelfIntersections(pair({p, q, Vec3(0.5, 1, 0)}, {q, p, Vec3(0.3, -0.5, 0)})).pairs, 0u);
    EXPECT_EQ(
        findSelfIntersections(pair({p, q, Vec3(0.5, 1, 0)}, {q, p, Vec3(0.3, 0.5, 0.4)})).pairs,
        0u);
}

TEST(SelfIntersections, ContactWithinRoundingIsNotACrossing) {
    // A vertex of the second triangle on the first's face, the rest above it, and the same
    // vertex pushed below the face by float-rounding size (1e-8 of coordinates ~1).
    for (const double dz : {0.0, -1e-8, 1e-8}) {
        const TriangleMesh m = pair({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
                                    {Vec3(0.1, 0, dz), Vec3(0.2, 0.3, 1), Vec3(0.2, -0.3, 1)});
        EXPECT_EQ(findSelfIntersections(m).pairs, 0u) << dz;
    }
    // A nearly parallel triangle whose corner is 1e-8 through the face: the segment where they
    // overlap is ~1e-5 long (longer than the tolerance), but it is a contact all the same.
    const TriangleMesh shallow =
        pair({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
             {Vec3(0.1, 0, -1e-8), Vec3(0.6, 0, 1e-3), Vec3(0.1, 0.5, 1e-3)});
    EXPECT_EQ(findSelfIntersections(shallow).pairs, 0u);
    // Pushed 1e-3 below: a crossing.
    const TriangleMesh deep = pair({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
                                   {Vec3(0.1, 0, -1e-3), Vec3(0.2, 0.3, 1), Vec3(0.2, -0.3, 1)});
    EXPECT_EQ(findSelfIntersections(deep).pairs, 1u);
}

TEST(SelfIntersections, TwoInterlockedCubesCrossAndThreadsAgree) {
    TriangleMesh m = cube();
    const TriangleMesh other = cube();
    const uint32_t base = uint32_t(m.positions.size());
    for (const Vec3& p : other.positions) m.positions.push_back(p + Vec3(0.5, 0.25, 0.125));
    for (const auto& t : other.triangles)
        m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    const SelfIntersections one = findSelfIntersections(m, 1e-6, 1);
    const SelfIntersections two = findSelfIntersections(m, 1e-6, 2);
    EXPECT_GT(one.pairs, 0u);
    EXPECT_EQ(one.pairs, two.pairs);
    EXPECT_EQ(one.exampleA, two.exampleA);
    EXPECT_EQ(one.exampleB, two.exampleB);
    // The example lies on both cubes' surfaces: inside the overlap box [0.5,1]x[0.25,1]x[0.125,1].
    EXPECT_GE(one.example.x, 0.5 - 1e-12);
    EXPECT_GE(one.example.y, 0.25 - 1e-12);
    EXPECT_GE(one.example.z, 0.125 - 1e-12);
}

// The octahedron of unit vertices, outward; vertex 4 is +z.
TriangleMesh octahedron() {
    TriangleMesh m;
    m.positions = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                   Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}

// The top vertex pulled down into the plane of its ring of neighbours and out past it: its
// triangles fold flat over each other (coplanar overlaps). Unfolding toward the top (its safe
// point) leaves it clean, part of the way there (the bisection stops at the first clean position it
// finds from the fold); toward a point as bad as the fold, it stays folded at that point and says
// so.
TEST(UnfoldVertices, FoldedStarMovesTowardItsSafePointUntilClean) {
    TriangleMesh folded = octahedron();
    const Vec3 pulled(2.0, 0.3, 0.0);
    folded.positions[4] = pulled;
    ASSERT_TRUE(checkTopology(folded).closedManifold());
    ASSERT_GT(findSelfIntersections(folded).pairs, 0u);
    const double tol = selfIntersectionTolerance(folded, 1e-6);

    std::vector<Vec3> safe(folded.positions.size(), Vec3(0.0));
    safe[4] = Vec3(0, 0, 1);
    TriangleMesh mesh = folded;
    const UnfoldStats s = unfoldVertices(mesh, {{4, 1}}, safe, tol, 1);
    EXPECT_EQ(s.movedGroups, 1u);
    EXPECT_EQ(s.unresolvedGroups, 0u);
    EXPECT_EQ(findSelfIntersections(mesh).pairs, 0u);
    const Vec3 along = mesh.positions[4] - pulled, whole = safe[4] - pulled;
    EXPECT_LT(glm::length(glm::cross(along, whole)), 1e-12);  // on the segment
    const double t = glm::dot(along, whole) / glm::dot(whole, whole);
    EXPECT_GT(t, 0.0);
    EXPECT_LT(t, 1.0);
    for (int v = 0; v < 6; ++v) {
        if (v != 4) {
            EXPECT_EQ(mesh.positions[size_t(v)], folded.positions[size_t(v)]);
        }
    }

    safe[4] = Vec3(2.0, -0.3, 0.0);
    TriangleMesh stuck = folded;
    const UnfoldStats bad = unfoldVertices(stuck, {{4, 1}}, safe, tol, 1);
    EXPECT_EQ(bad.movedGroups, 0u);
    EXPECT_EQ(bad.unresolvedGroups, 1u);
    EXPECT_EQ(stuck.positions[4], safe[4]);

    // A clean mesh is left alone.
    TriangleMesh clean = octahedron();
    safe[4] = Vec3(0.0);
    EXPECT_EQ(unfoldVertices(clean, {{4, 1}}, safe, tol, 1).foldedGroups, 0u);
    EXPECT_EQ(clean.positions[4], Vec3(0, 0, 1));
}

// A fan of 7 triangles around vertex 0 in the plane z = 0, its ring at steps of turns/7 of a
// full turn. Every triangle turns the same way around the vertex (each step is less than half a
// turn), so only the angles' sum tells a disk (turns = 1) from a star that winds twice over
// itself (turns = 2: coplanar overlaps).
TriangleMesh planarFan(int turns) {
    constexpr int kRing = 7;
    TriangleMesh m;
    m.positions.push_back(Vec3(0.0));
    for (int i = 0; i < kRing; ++i) {
        const double angle = 2.0 * std::numbers::pi * turns * i / kRing;
        m.positions.push_back(Vec3(std::cos(angle), std::sin(angle), 0.0));
    }
    for (uint32_t i = 0; i < kRing; ++i) m.triangles.push_back({0, 1 + i, 1 + (i + 1) % kRing});
    return m;
}

// The quick certificate that passes a vertex without testing its triangles pair by pair (all
// of them turning one way around it, seen along their mean normal, and their angles there
// adding up to one full turn) must not pass a star that winds twice: without the full-turn
// condition it would, and the overlaps would be missed.
TEST(UnfoldVertices, AStarThatWindsTwiceIsFoundFolded) {
    const TriangleMesh twice = planarFan(2);
    ASSERT_GT(findSelfIntersections(twice).pairs, 0u);
    const double tol = selfIntersectionTolerance(twice, 1e-6);
    EXPECT_EQ(findFoldedGroups(twice, {{0, 1}}, tol, 1), std::vector<uint32_t>{0});

    // The disk passes on the certificate alone: no pair of its triangles is tested.
    TriangleMesh disk = planarFan(1);
    ASSERT_EQ(findSelfIntersections(disk).pairs, 0u);
    EXPECT_TRUE(findFoldedGroups(disk, {{0, 1}}, tol, 1).empty());
    const std::vector<Vec3> safe(disk.positions.size(), Vec3(0.0));
    const UnfoldStats s = unfoldVertices(disk, {{0, 1}}, safe, tol, 1);
    EXPECT_EQ(s.checkedGroups, 1u);
    EXPECT_EQ(s.pairwiseGroups, 0u);
    EXPECT_EQ(s.foldedGroups, 0u);
}

// A sheet vertex's star from csg_grid's GLB at T = 0.013 (vertex 0, clamped 1e-3 h inside the
// cell face x = 0.8104531, float coordinates): two of its neighbours, (4 0 5) and (8 5 0), lie
// almost in that face, seen edge-on along the star's mean normal, and fold 8 degrees apart
// across their edge 0-5; the second is a sliver 3e-5 wide. Every triangle turns the same way
// seen along the mean and the angles add up to one turn, yet the pair test finds the two
// overlapping within its coplanarity tolerance. The certificate must not pass it: neighbours
// facing more than 90 degrees apart send a star to the pair test (without that, the unfolding
// never saw this cell and the GLB kept the pair).
TEST(UnfoldVertices, NeighboursFoldedFlatWithinTheToleranceAreFoundFolded) {
    TriangleMesh star;
    star.positions = {{0.81046903133392334, 0.072003215551377009, 2.95116138458252},
                      {0.81832945346832275, 0.060693595558405589, 2.948065042495728},
                      {0.82371342182159424, 0.061364781111479472, 2.947914838790894},
                      {0.81307852268218994, 0.060038994997740458, 2.9482116699218754},
                      {0.81045305728912354, 0.060693595558405589, 2.9485051631927495},
                      {0.81045305728912354, 0.076615631580353449, 2.9520716667175297},
                      {0.82640540599822998, 0.062707155942917536, 2.948065042495728},
                      {0.8343815803527832, 0.070670880377293299, 2.9494035243988042},
                      {0.81045305728912354, 0.076645925641060542, 2.952067613601685},
                      {0.81046748161315918, 0.076645925641060542, 2.9520776271820073},
                      {0.82640540599822998, 0.076645925641060542, 2.9511876106262211}};
    star.triangles = {{1, 2, 0}, {1, 0, 3}, {4, 3, 0}, {4, 0, 5},  {6, 0, 2},
                      {6, 7, 0}, {8, 5, 0}, {8, 0, 9}, {10, 0, 7}, {10, 9, 0}};
    const SelfIntersections x = findSelfIntersections(star);
    ASSERT_EQ(x.pairs, 1u);
    ASSERT_EQ(x.coplanarPairs, 1u);
    const double tol = selfIntersectionTolerance(star, 1e-6);
    EXPECT_EQ(findFoldedGroups(star, {{0, 1}}, tol, 1), std::vector<uint32_t>{0});
}

}  // namespace
}  // namespace csg
