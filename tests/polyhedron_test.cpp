// The mesh primitive (primitives/Polyhedron.h) against spans worked out by hand (a cube in both
// windings, a tetrahedron, an L-shaped prism whose caps are non-convex faces), and the edge
// rule's promises on a faceted sphere: a ray through a vertex or an edge gives the spans of the
// same ray nudged by one ulp, a ray grazing an edge or a face never breaks the pairing, and the
// crossing count of every line is even. Also: the capacity rule, an open mesh's answer, face
// ids beyond 65535 triangles, and the lecture's two polygon methods (Snyder's, Marchal's):
// spans by hand, agreement away from edges, a shared edge counted twice, interpolated normals.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "primitives/Polyhedron.h"
#include "primitives/solvers/LinePoint.h"
#include "tests/HintedSpans.h"

using namespace csg;

namespace {

struct MeshInput {
    std::vector<Vec3> points;
    PolygonFaces faces;
};

// The unit cube [0, 1]^3 with quad faces, wound as OpenSCAD wants them (clockwise from outside)
// or the other way.
MeshInput cube(bool openscadWinding) {
    MeshInput m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    // OpenSCAD's documentation cube: clockwise seen from outside.
    std::vector<std::vector<uint32_t>> quads = {{0, 1, 2, 3}, {4, 5, 1, 0}, {7, 6, 5, 4},
                                                {5, 6, 2, 1}, {6, 7, 3, 2}, {7, 4, 0, 3}};
    for (auto& q : quads) {
        if (!openscadWinding) std::reverse(q.begin(), q.end());
        m.faces.corners.insert(m.faces.corners.end(), q.begin(), q.end());
        m.faces.closeFace();
    }
    return m;
}

// A UV sphere of radius r: `rings` rings between two poles, `sectors` vertices per ring, each
// coordinate rounded to a multiple of 2^-quantBits (so edge midpoints are exact and rays along
// the axes can pass exactly through vertices and edges); triangles only.
MeshInput sphere(int sectors, int rings, double r, int quantBits = 20) {
    MeshInput m;
    const double q = std::ldexp(1.0, quantBits);
    auto quantize = [&](Vec3 p) { return glm::round(p * q) / q; };
    m.points.push_back(quantize(Vec3(0, 0, r)));
    for (int i = 1; i < rings; ++i) {
        const double polar = M_PI * i / rings;
        for (int k = 0; k < sectors; ++k) {
            const double az = 2 * M_PI * k / sectors;
            m.points.push_back(quantize(r * Vec3(std::sin(polar) * std::cos(az),
                                                 std::sin(polar) * std::sin(az), std::cos(polar))));
        }
    }
    m.points.push_back(quantize(Vec3(0, 0, -r)));
    const uint32_t south = uint32_t(m.points.size() - 1);
    auto ring = [&](int i, int k) { return uint32_t(1 + (i - 1) * sectors + (k % sectors)); };
    for (int k = 0; k < sectors; ++k) m.faces.add({0, ring(1, k + 1), ring(1, k)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int k = 0; k < sectors; ++k) {
            m.faces.add({ring(i, k), ring(i, k + 1), ring(i + 1, k + 1)});
            m.faces.add({ring(i, k), ring(i + 1, k + 1), ring(i + 1, k)});
        }
    for (int k = 0; k < sectors; ++k)
        m.faces.add({south, ring(rings - 1, k), ring(rings - 1, k + 1)});
    return m;
}

Polyhedron build(const MeshInput& m) {
    Polyhedron p = Polyhedron::make(m.points, m.faces);
    EXPECT_EQ(p.invalidReason(), nullptr) << p.invalidReason();
    return p;
}

struct SpanEnds {
    double in, out;
    uint16_t faceIn, faceOut;
};

// spans() as csg/ calls it: the line restarted at its entry into the box, t shifted back.
std::vector<SpanEnds> spansOf(const Polyhedron& p, const Vec3& o, const Vec3& d) {
    double t0 = -kInfinity, t1 = kInfinity;
    if (!clipToBox(SlabRay(o, d), p.bounds(), t0, t1)) return {};
    const double shift = std::isfinite(t0) ? t0 : 0.0;
    LocalSpans local;
    p.spans(pointOnLine(o, d, shift), d, local);
    std::vector<SpanEnds> out;
    for (int i = 0; i < local.count; ++i) {
        const auto& e = local.entries[i];
        out.push_back({e.tIn + shift, e.tOut + shift, e.faceIn, e.faceOut});
    }
    return out;
}

// The spans of a line, of positive length (the caller drops touches), as [in, out] pairs.
std::vector<std::pair<double, double>> solidSpans(const Polyhedron& p, const Vec3& o, const Vec3& d,
                                                  double minLength) {
    std::vector<std::pair<double, double>> out;
    for (const SpanEnds& s : spansOf(p, o, d))
        if (s.out - s.in > minLength) out.push_back({s.in, s.out});
    return out;
}

std::string str(const Vec3& v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}

bool sameSpans(const std::vector<std::pair<double, double>>& a,
               const std::vector<std::pair<double, double>>& b, double tolerance) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::abs(a[i].first - b[i].first) > tolerance ||
            std::abs(a[i].second - b[i].second) > tolerance)
            return false;
    return true;
}

// The origin moved by one ulp along each axis perpendicular to d, both ways.
std::vector<Vec3> nudges(const Vec3& o, const Vec3& d) {
    std::vector<Vec3> out;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) == std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)})) continue;
        for (double toward : {kInfinity, -kInfinity}) {
            Vec3 q = o;
            q[a] = std::nextafter(q[a], toward);
            out.push_back(q);
        }
    }
    return out;
}

TEST(Polyhedron, CubeSpansByHandInBothWindings) {
    for (bool openscadWinding : {true, false}) {
        SCOPED_TRACE(openscadWinding ? "clockwise" : "counter-clockwise");
        const Polyhedron p = build(cube(openscadWinding));
        EXPECT_EQ(p.triangleCount(), 12u);
        EXPECT_TRUE(p.edges().manifold());
        EXPECT_EQ(p.edges().misoriented, 0u);
        EXPECT_EQ(p.bounds().lo, Vec3(0.0));
        EXPECT_EQ(p.bounds().hi, Vec3(1.0));
        // Straight through along z: enters z = 0 at t = 1, leaves z = 1 at t = 2.
        auto s = spansOf(p, Vec3(0.25, 0.5, -1), Vec3(0, 0, 1));
        ASSERT_EQ(s.size(), 1u);
        EXPECT_DOUBLE_EQ(s[0].in, 1.0);
        EXPECT_DOUBLE_EQ(s[0].out, 2.0);
        // The normals there point out of the cube, whichever way the faces were wound.
        EXPECT_EQ(p.normal(Vec3(0.25, 0.5, 0), s[0].faceIn), Vec3(0, 0, -1));
        EXPECT_EQ(p.normal(Vec3(0.25, 0.5, 1), s[0].faceOut), Vec3(0, 0, 1));
        // A slanted ray, d not unit: x = -1 + 2t enters at t = 0.5 and leaves at t = 1 through
        // x = 1 (y = 0.2 + 0.3t and z = 0.9 - 0.6t stay inside there).
        s = spansOf(p, Vec3(-1, 0.2, 0.9), Vec3(2, 0.3, -0.6));
        ASSERT_EQ(s.size(), 1u);
        EXPECT_NEAR(s[0].in, 0.5, 1e-15);
        EXPECT_NEAR(s[0].out, 1.0, 1e-15);
        EXPECT_EQ(p.normal(Vec3(0, 0.35, 0.6), s[0].faceIn), Vec3(-1, 0, 0));
        // A ray through a corner only touches; one along the diagonal runs corner to corner.
        EXPECT_TRUE(solidSpans(p, Vec3(-1, 1, 1), Vec3(1, -1, -1), 0.0).empty());
        s = spansOf(p, Vec3(-1, -1, -1), Vec3(1, 1, 1));
        ASSERT_EQ(s.size(), 1u);
        EXPECT_DOUBLE_EQ(s[0].in, 1.0);
        EXPECT_DOUBLE_EQ(s[0].out, 2.0);
        // Misses, and points inside and out.
        EXPECT_TRUE(spansOf(p, Vec3(1.5, 0.5, -1), Vec3(0, 0, 1)).empty());
        EXPECT_TRUE(p.inside(Vec3(0.3, 0.6, 0.2)));
        EXPECT_FALSE(p.inside(Vec3(1.3, 0.6, 0.2)));
        EXPECT_FALSE(p.inside(Vec3(0.3, -0.01, 0.2)));
    }
}

TEST(Polyhedron, SomeFacesTurnedIsTheSameSolid) {
    MeshInput m = cube(true);
    // Turn two faces: parity does not see winding; the warning counts the edges.
    std::reverse(m.faces.corners.begin(), m.faces.corners.begin() + 4);
    std::reverse(m.faces.corners.begin() + 8, m.faces.corners.begin() + 12);
    const Polyhedron p = build(m);
    EXPECT_TRUE(p.edges().closed());
    EXPECT_GT(p.edges().misoriented, 0u);
    const auto s = spansOf(p, Vec3(0.5, 0.5, 3), Vec3(0, 0, -1));
    ASSERT_EQ(s.size(), 1u);
    EXPECT_DOUBLE_EQ(s[0].in, 2.0);
    EXPECT_DOUBLE_EQ(s[0].out, 3.0);
    EXPECT_EQ(p.normal(Vec3(0.5, 0.5, 1), s[0].faceIn), Vec3(0, 0, 1));
    EXPECT_EQ(p.normal(Vec3(0.5, 0.5, 0), s[0].faceOut), Vec3(0, 0, -1));
}

TEST(Polyhedron, TetrahedronByHand) {
    // Corners at the origin and the unit points: the solid x, y, z >= 0, x + y + z <= 1.
    MeshInput m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.faces.add({0, 1, 2});
    m.faces.add({0, 3, 1});
    m.faces.add({0, 2, 3});
    m.faces.add({1, 3, 2});
    const Polyhedron p = build(m);
    // Along z at (0.2, 0.3): from z = 0 to z = 1 - 0.5 = 0.5.
    auto s = spansOf(p, Vec3(0.2, 0.3, -2), Vec3(0, 0, 1));
    ASSERT_EQ(s.size(), 1u);
    EXPECT_DOUBLE_EQ(s[0].in, 2.0);
    EXPECT_NEAR(s[0].out, 2.5, 1e-15);
    const Vec3 slanted = p.normal(Vec3(0.2, 0.3, 0.5), s[0].faceOut);
    EXPECT_NEAR(glm::dot(slanted, glm::normalize(Vec3(1, 1, 1))), 1.0, 1e-15);
    // Along (1, 1, 1) from the origin's far side: in at the origin, out on x + y + z = 1.
    s = spansOf(p, Vec3(-1, -1, -1), Vec3(1, 1, 1));
    ASSERT_EQ(s.size(), 1u);
    EXPECT_DOUBLE_EQ(s[0].in, 1.0);
    EXPECT_NEAR(s[0].out, 1.0 + 1.0 / 3.0, 1e-15);
    EXPECT_TRUE(p.inside(Vec3(0.1, 0.1, 0.1)));
    EXPECT_FALSE(p.inside(Vec3(0.4, 0.4, 0.4)));
}

TEST(Polyhedron, NonConvexFacesAreEarClipped) {
    // An L-shaped prism, its two caps one 6-corner face each: [0,2]x[0,1] u [0,1]x[1,2], z in
    // [0, 1]. The notch [1,2]x[1,2] is empty.
    MeshInput m;
    const Vec2 outline[6] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    for (double z : {0.0, 1.0})
        for (const Vec2& p : outline) m.points.emplace_back(p.x, p.y, z);
    m.faces.add({5, 4, 3, 2, 1, 0});
    m.faces.add({6, 7, 8, 9, 10, 11});
    for (uint32_t i = 0; i < 6; ++i) {
        const uint32_t j = (i + 1) % 6;
        m.faces.add({i, j, j + 6, i + 6});
    }
    const Polyhedron p = build(m);
    EXPECT_TRUE(p.edges().manifold());
    // Down through the notch: nothing; through each arm: z from 1 to 0.
    EXPECT_TRUE(spansOf(p, Vec3(1.5, 1.5, 3), Vec3(0, 0, -1)).empty());
    for (const Vec2& at : {Vec2(1.5, 0.5), Vec2(0.5, 1.5), Vec2(0.5, 0.5)}) {
        const auto s = spansOf(p, Vec3(at, 3), Vec3(0, 0, -1));
        ASSERT_EQ(s.size(), 1u);
        EXPECT_DOUBLE_EQ(s[0].in, 2.0);
        EXPECT_DOUBLE_EQ(s[0].out, 3.0);
        EXPECT_EQ(p.normal(Vec3(at, 1), s[0].faceIn), Vec3(0, 0, 1));
    }
    // Along x at y = 1.5: only the arm x in [0, 1].
    const auto s = spansOf(p, Vec3(-1, 1.5, 0.5), Vec3(1, 0, 0));
    ASSERT_EQ(s.size(), 1u);
    EXPECT_DOUBLE_EQ(s[0].in, 1.0);
    EXPECT_DOUBLE_EQ(s[0].out, 2.0);
}

// Every line through a vertex, through an edge (axis-aligned rays of a quantized sphere pass
// exactly through them) gives the spans of the same line nudged by one ulp; the crossing count
// is always even.
TEST(Polyhedron, VertexAndEdgeRaysMatchNudgedRays) {
    const MeshInput m = sphere(24, 12, 1.0);
    const Polyhedron p = build(m);
    ASSERT_TRUE(p.edges().manifold());
    std::vector<Vec3> targets = m.points;
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = m.points[m.faces.corners[3 * f + k]];
            const Vec3 b = m.points[m.faces.corners[3 * f + (k + 1) % 3]];
            targets.push_back(0.5 * (a + b));  // exact: the coordinates are multiples of 2^-20
        }
    std::vector<Polyhedron::Crossing> crossings;
    int transversal = 0, grazing = 0;
    for (const Vec3& target : targets)
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 d(0.0);
            d[axis] = axis == 1 ? -1.0 : 1.0;
            Vec3 o = target;
            o[axis] = -4.0 * d[axis];
            p.crossings(o, d, crossings);
            ASSERT_EQ(crossings.size() % 2, 0u) << "target " << str(target);
            const auto exact = solidSpans(p, o, d, 1e-12);
            // Grazing where the target lies near the sphere's silhouette seen along the axis:
            // the nudges there may go in or out, and the exact line must match one of them.
            Vec3 across = target;
            across[axis] = 0.0;
            const bool nearSilhouette = glm::length(across) > 0.9;
            int matches = 0, tried = 0;
            for (const Vec3& q : nudges(o, d)) {
                ++tried;
                matches += sameSpans(exact, solidSpans(p, q, d, 1e-12), 1e-9);
            }
            if (nearSilhouette) {
                ++grazing;
                EXPECT_GE(matches, 1) << "grazing target " << str(target);
            } else {
                ++transversal;
                EXPECT_EQ(matches, tried) << "target " << str(target) << " axis " << axis;
                EXPECT_EQ(exact.size(), 1u);
            }
        }
    EXPECT_GT(transversal, 1000);
    EXPECT_GT(grazing, 50);
}

// A line that contains an edge of the sphere lies in the planes of the edge's two triangles:
// it touches the surface along the edge, or runs just inside, and where along the edge a
// crossing of those triangles sits is arbitrary (the rounded projection makes them slivers
// around the line). Never an odd count, and off the edge [4, 5] the answer of a nudged line.
TEST(Polyhedron, RaysAlongEdgesKeepPairs) {
    const MeshInput m = sphere(16, 8, 1.0, 12);
    const Polyhedron p = build(m);
    std::vector<Polyhedron::Crossing> crossings;
    // The spans with [4, 5] cut out (pieces of rounding length left there dropped).
    const auto offEdge = [](std::vector<std::pair<double, double>> spans) {
        std::vector<std::pair<double, double>> out;
        for (const auto& [in, outT] : spans) {
            if (std::min(outT, 4.0) - in > 1e-6) out.push_back({in, std::min(outT, 4.0)});
            if (outT - std::max(in, 5.0) > 1e-6) out.push_back({std::max(in, 5.0), outT});
        }
        return out;
    };
    for (size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = m.points[m.faces.corners[3 * f + k]];
            const Vec3 b = m.points[m.faces.corners[3 * f + (k + 1) % 3]];
            const Vec3 d = b - a;        // exact (12-bit coordinates)
            const Vec3 o = a - 4.0 * d;  // exact: o + 4 d = a, o + 5 d = b
            p.crossings(o, d, crossings);
            ASSERT_EQ(crossings.size() % 2, 0u);
            const auto exact = offEdge(solidSpans(p, o, d, 1e-12));
            int matches = 0;
            for (const Vec3& q : nudges(o, d))
                matches += sameSpans(exact, offEdge(solidSpans(p, q, d, 1e-12)), 1e-6);
            EXPECT_GE(matches, 1) << "edge " << str(a) << " " << str(b);
        }
}

// Lines in the plane of a face (the cube's top) and along its edges: 0 or 2 crossings there.
TEST(Polyhedron, GrazingFacesAndEdgesKeepPairs) {
    const Polyhedron p = build(cube(true));
    std::vector<Polyhedron::Crossing> crossings;
    const Vec3 origins[] = {{-1, 0.5, 1}, {-1, 0, 1}, {-1, 1, 0}, {0.5, -1, 0}, {-1, 0.3, 0}};
    for (const Vec3& o : origins)
        for (const Vec3& d : {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(1, 0.5, 0)}) {
            p.crossings(o, d, crossings);
            EXPECT_EQ(crossings.size() % 2, 0u) << str(o) << str(d);
            const auto exact = solidSpans(p, o, d, 1e-12);
            int matches = 0;
            for (const Vec3& q : nudges(o, d))
                matches += sameSpans(exact, solidSpans(p, q, d, 1e-12), 1e-12);
            EXPECT_GE(matches, 1) << str(o) << str(d);
        }
}

// Seeded random lines through random vertices of a bumpy closed mesh: always an even count.
TEST(Polyhedron, RandomLinesThroughVerticesPair) {
    MeshInput m = sphere(40, 20, 1.0);
    std::mt19937_64 rng(18);
    std::uniform_real_distribution<double> bump(0.7, 1.0), u(-1.0, 1.0);
    for (Vec3& q : m.points) q *= bump(rng);
    const Polyhedron p = build(m);
    std::vector<Polyhedron::Crossing> crossings;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 v = m.points[rng() % m.points.size()];
        const Vec3 d(u(rng), u(rng), u(rng));
        p.crossings(v - 3.0 * d, d, crossings);
        ASSERT_EQ(crossings.size() % 2, 0u) << i;
    }
}

// LocalSpans' hints on closed meshes (tests/HintedSpans.h): a closest() or any() that reads
// only the first span past `from` gets it from the crossings up to a horizon near its entry,
// its exit early where that lies farther, and the whole list where the ray starts inside a
// span. Over a bumpy sphere (lines meet it in several spans, some through its vertices) and
// three boxes in a row, one thin and one a sliver of a gap from the first (short spans and
// gaps against a margin of 1e-6 or 0.1).
TEST(Polyhedron, FirstSpanHintsArePrefixesOfTheWholeList) {
    MeshInput ball = sphere(40, 20, 1.0);
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> bump(0.6, 1.0), u(-1.0, 1.0), unit(0.0, 1.0);
    for (Vec3& q : ball.points) q *= bump(rng);
    MeshInput row;
    for (const auto& [lo, hi] : {std::pair{0.0, 1.0}, {1.05, 1.1}, {1.5, 2.5}}) {
        const MeshInput c = cube(true);
        const uint32_t base = static_cast<uint32_t>(row.points.size());
        for (const Vec3& q : c.points) row.points.push_back({lo + (hi - lo) * q.x, q.y, q.z});
        for (size_t f = 0; f + 1 < c.faces.faceStart.size(); ++f) {
            for (uint32_t k = c.faces.faceStart[f]; k < c.faces.faceStart[f + 1]; ++k)
                row.faces.corners.push_back(base + c.faces.corners[k]);
            row.faces.closeFace();
        }
    }
    int earlyEnds = 0, placeholders = 0;
    for (const MeshInput* m : {&ball, &row}) {
        const Polyhedron p = build(*m);
        ASSERT_TRUE(p.edges().closed());
        const Bounds3 box = p.bounds();
        for (int i = 0; i < 20000; ++i) {
            Vec3 d(u(rng), u(rng), u(rng));
            if (i % 5 == 0) d = Vec3(1.0, 0.01 * u(rng), 0.01 * u(rng));  // along the row
            d = glm::normalize(d);
            // Through a random point, or through a vertex.
            const Vec3 through =
                i % 3 == 0 ? m->points[rng() % m->points.size()]
                           : box.lo + Vec3(unit(rng), unit(rng), unit(rng)) * box.extent();
            const Vec3 o = through - 4.0 * d;
            const double from = 8.0 * unit(rng);
            const double margin = rng() % 2 ? 1e-6 : 0.1;
            SCOPED_TRACE(::testing::Message()
                         << "mesh " << (m == &ball ? "ball" : "row") << ", line " << i);
            csg::testing::expectHintedPrefix(p, o, d, from, margin, rng() % 2 == 0, earlyEnds,
                                             placeholders);
            if (HasFatalFailure()) return;
        }
    }
    // The hints must have saved work, or this test tests nothing.
    EXPECT_GT(earlyEnds, 1000);
    EXPECT_GT(placeholders, 1000);
}

// 40 slabs along x: more spans than LocalSpans holds. The 8 narrowest gaps close; the first
// entry and the last exit stay.
TEST(Polyhedron, MoreSpansThanCapacityCloseTheNarrowestGaps) {
    MeshInput m;
    const int slabs = 40;
    double x = 0.0;
    std::vector<double> gapAfter;
    for (int i = 0; i < slabs; ++i) {
        const double x1 = x + 1.0;
        const MeshInput c = cube(false);
        const uint32_t base = uint32_t(m.points.size());
        for (const Vec3& q : c.points) m.points.emplace_back(x + (x1 - x) * q.x, q.y, q.z);
        for (uint32_t f = 0; f < c.faces.size(); ++f) {
            for (uint32_t k = c.faces.faceStart[f]; k < c.faces.faceStart[f + 1]; ++k)
                m.faces.corners.push_back(base + c.faces.corners[k]);
            m.faces.closeFace();
        }
        // Gaps 0.5, except every fifth is 0.25 (those close first): 7 of them, plus the first
        // of the 0.5 gaps.
        const double gap = i % 5 == 4 ? 0.25 : 0.5;
        gapAfter.push_back(gap);
        x = x1 + gap;
    }
    const Polyhedron p = build(m);
    const auto s = spansOf(p, Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0));
    ASSERT_EQ(s.size(), size_t(LocalSpans::kCapacity));
    EXPECT_DOUBLE_EQ(s.front().in, 1.0);
    EXPECT_DOUBLE_EQ(s.back().out, 1.0 + x - gapAfter.back());
    // The first span runs over slab 0, the first 0.5 gap, and slab 1.
    EXPECT_DOUBLE_EQ(s[0].out, 1.0 + 2.5);
    for (size_t i = 1; i < s.size(); ++i) EXPECT_GE(s[i].in - s[i - 1].out, 0.5 - 1e-12);
}

TEST(Polyhedron, OpenMeshDropsTheLastCrossingOfAnOddLine) {
    MeshInput m = cube(true);
    m.faces.corners.resize(m.faces.faceStart[5]);  // no face at x = 0
    m.faces.faceStart.resize(6);
    const Polyhedron p = build(m);
    EXPECT_FALSE(p.edges().closed());
    EXPECT_EQ(p.edges().openEdges, 4u);
    // Along x through the hole: one crossing (x = 1), dropped.
    EXPECT_TRUE(spansOf(p, Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)).empty());
    // Along y: both walls are there.
    EXPECT_EQ(spansOf(p, Vec3(0.5, -1, 0.5), Vec3(0, 1, 0)).size(), 1u);
}

// Beyond 65535 triangles a face id names a residue; normal() finds the crossed triangle.
TEST(Polyhedron, FaceIdsOfLargeMeshes) {
    const MeshInput m = sphere(400, 200, 2.0);
    const Polyhedron p = build(m);
    ASSERT_GT(p.triangleCount(), 2 * size_t(Polyhedron::kFaceIds));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Polyhedron::Crossing> crossings;
    for (int i = 0; i < 300; ++i) {
        const Vec3 o = 6.0 * glm::normalize(Vec3(u(rng), u(rng), u(rng)));
        const Vec3 d = Vec3(u(rng), u(rng), u(rng)) - o;
        p.crossings(o, d, crossings);
        for (const auto& c : crossings) {
            const auto& t = p.data->triangles[c.triangle];
            const Vec3 &a = p.data->vertices[t[0]], &b = p.data->vertices[t[1]],
                       &e = p.data->vertices[t[2]];
            const Vec3 expected = glm::normalize(glm::cross(b - a, e - a));
            const Vec3 n = p.normal(pointOnLine(o, d, c.t), uint16_t(c.triangle % 65535));
            EXPECT_NEAR(glm::dot(n, expected), 1.0, 1e-12);
            // Outward: away from the sphere's centre.
            EXPECT_GT(glm::dot(n, a), 0.0);
        }
    }
}

TEST(Polyhedron, TriangleSoupWeldsAndTurnsIntoTheIndexedSolid) {
    // The UV sphere as an STL holds it: every triangle with three corners of its own, the zero
    // coordinates of every other triangle written -0, and a seeded third of the triangles
    // turned. The poles are hubs of 64 edges (the sort of a vertex's many edges), the ring
    // vertices have 6. Expected by hand: S (R - 1) welded vertices and 3 S (R - 1) edges, none
    // open; the misoriented edges counted here from the indexed mesh's own edge map.
    constexpr int kSectors = 64, kRings = 12;
    const MeshInput indexed = sphere(kSectors, kRings, 1.0);
    const size_t triangles = indexed.faces.size();
    ASSERT_EQ(triangles, size_t(2 * kSectors * (kRings - 1)));
    std::mt19937_64 rng(11);
    std::vector<bool> turned(triangles);
    MeshInput soup;
    for (size_t f = 0; f < triangles; ++f) {
        turned[f] = rng() % 3 == 0;
        std::array<uint32_t, 3> c;
        for (int k = 0; k < 3; ++k) c[k] = indexed.faces.corners[indexed.faces.faceStart[f] + k];
        if (turned[f]) std::swap(c[1], c[2]);
        const uint32_t first = uint32_t(soup.points.size());
        for (const uint32_t v : c) {
            Vec3 q = indexed.points[v];
            if (f % 2 == 1)
                for (int a = 0; a < 3; ++a)
                    if (q[a] == 0.0) q[a] = -0.0;
            soup.points.push_back(q);
        }
        soup.faces.add({first, first + 1, first + 2});
    }
    std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> users;
    for (size_t f = 0; f < triangles; ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = indexed.faces.corners[indexed.faces.faceStart[f] + k];
            const uint32_t b = indexed.faces.corners[indexed.faces.faceStart[f] + (k + 1) % 3];
            users[{std::min(a, b), std::max(a, b)}].push_back(f);
        }
    uint64_t misoriented = 0;
    for (const auto& [edge, fs] : users) {
        ASSERT_EQ(fs.size(), 2u);
        misoriented += turned[fs[0]] != turned[fs[1]];
    }
    ASSERT_GT(misoriented, 0u);

    const Polyhedron p = build(soup);
    EXPECT_EQ(p.data->vertices.size(), size_t(kSectors * (kRings - 1) + 2));
    EXPECT_EQ(p.edges().edges, uint64_t(3 * kSectors * (kRings - 1)));
    EXPECT_EQ(p.edges().edges, users.size());
    EXPECT_EQ(p.edges().openEdges, 0u);
    EXPECT_EQ(p.edges().manyFaces, 0u);
    EXPECT_EQ(p.edges().misoriented, misoriented);
    // One sheet turned outward: every normal points away from the centre, and lines answer as
    // through the indexed sphere.
    const Polyhedron q = build(indexed);
    for (uint32_t t = 0; t < p.data->triangles.size(); ++t) {
        const auto& c = p.data->triangles[t];
        const Vec3 &a = p.data->vertices[c[0]], &b = p.data->vertices[c[1]],
                   &e = p.data->vertices[c[2]];
        EXPECT_GT(glm::dot(glm::cross(b - a, e - a), a + b + e), 0.0) << "triangle " << t;
    }
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const Vec3 o = 3.0 * glm::normalize(Vec3(u(rng), u(rng), u(rng)));
        const Vec3 d = 0.5 * Vec3(u(rng), u(rng), u(rng)) - o;
        const auto a = spansOf(p, o, d), b = spansOf(q, o, d);
        ASSERT_EQ(a.size(), b.size()) << "line " << i;
        for (size_t k = 0; k < a.size(); ++k) {
            EXPECT_EQ(a[k].in, b[k].in) << "line " << i;
            EXPECT_EQ(a[k].out, b[k].out) << "line " << i;
        }
    }
}

TEST(Polyhedron, DegenerateInput) {
    // Faces with repeated or too few distinct corners have no area: dropped. None left: the
    // empty solid's reason.
    MeshInput m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}};
    m.faces.add({0, 1, 2});  // corners 0 and 2 weld
    m.faces.add({1, 1, 0});
    EXPECT_EQ(Polyhedron::make(m.points, m.faces).invalidReason(), Polyhedron::kNoFaces);
    m.points[0].x = std::nan("");
    EXPECT_NE(Polyhedron::make(m.points, m.faces).invalidReason(), nullptr);
}

// ---- the lecture's polygon methods (--polygon-method) ----

Polyhedron withMethod(Polyhedron p, PolygonMethod method) {
    p.method = method;
    return p;
}

constexpr PolygonMethod kLectureMethods[] = {PolygonMethod::Snyder, PolygonMethod::Marchal};

// Rays through face interiors: the cube's spans by hand, the same for every method.
TEST(PolygonMethods, CubeSpansByHand) {
    const Polyhedron cube1 = build(cube(true));
    for (PolygonMethod method : kLectureMethods) {
        SCOPED_TRACE(polygonMethodName(method));
        const Polyhedron p = withMethod(cube1, method);
        // Along +x at (0.3, 0.4): in at x = 0 (t = 1), out at x = 1 (t = 2).
        auto s = solidSpans(p, Vec3(-1, 0.3, 0.4), Vec3(1, 0, 0), 0.0);
        ASSERT_EQ(s.size(), 1u);
        EXPECT_NEAR(s[0].first, 1.0, 1e-15);
        EXPECT_NEAR(s[0].second, 2.0, 1e-15);
        // A slanted line from (0.1, 0.2, -1) along (0.25, 0.25, 1): in through the bottom at
        // (0.35, 0.45, 0) (t = 1), out through the top at (0.6, 0.7, 1) (t = 2), both off the
        // quads' diagonals.
        s = solidSpans(p, Vec3(0.1, 0.2, -1), Vec3(0.25, 0.25, 1), 0.0);
        ASSERT_EQ(s.size(), 1u);
        EXPECT_NEAR(s[0].first, 1.0, 1e-15);
        EXPECT_NEAR(s[0].second, 2.0, 1e-15);
    }
}

// Where two triangles share an edge, each method decides each triangle alone: a line through
// the diagonal of the cube's x = 0 and x = 1 faces (both quads are cut along it or its
// mirror: y = z at x = 0 holds an edge of the ear-clipped quad) is counted by both triangles
// in Snyder's closed test, whose four crossings pair into two touches: no span. Watertight
// counts each face once.
TEST(PolygonMethods, SnyderCountsASharedEdgeTwice) {
    const Polyhedron cube1 = build(cube(true));
    std::vector<Polyhedron::Crossing> watertight;
    cube1.crossings(Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), watertight);
    ASSERT_EQ(watertight.size(), 2u);
    const auto s = solidSpans(cube1, Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), 0.0);
    ASSERT_EQ(s.size(), 1u);
    // Whether the diagonal through (0.5, 0.5) is an edge of both faces' triangulations, read
    // from the mesh: then Snyder's line sees two touches.
    const auto& d = *cube1.data;
    int diagonals = 0;
    for (const auto& t : d.triangles)
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = d.vertices[t[k]], b = d.vertices[t[(k + 1) % 3]];
            const Vec3 mid = 0.5 * (a + b);
            diagonals += a.x == b.x && mid.y == 0.5 && mid.z == 0.5;
        }
    // Each diagonal edge is seen from its two triangles: two faces, two uses each.
    ASSERT_EQ(diagonals, 4) << "the cube's quads are not cut through their centres";
    const Polyhedron snyder = withMethod(cube1, PolygonMethod::Snyder);
    EXPECT_TRUE(solidSpans(snyder, Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), 0.0).empty());
}

// Lines through random interior points of a faceted sphere's triangles (barycentric weights
// at least 0.05, far from every edge in rounded arithmetic): all three methods find the same
// spans, to the rounding of their different formulas.
TEST(PolygonMethods, AgreeAwayFromEdges) {
    const Polyhedron sphere24 = build(sphere(24, 12, 1.0));
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto& d = *sphere24.data;
    int compared = 0;
    for (int n = 0; n < 2000; ++n) {
        const auto& t = d.triangles[random() % d.triangles.size()];
        double b1 = 0.05 + 0.9 * unit(random), b2 = 0.05 + 0.9 * unit(random);
        if (b1 + b2 > 0.95) b1 = 1.0 - b1, b2 = 1.0 - b2;
        if (b1 + b2 > 0.95 || b1 < 0.05 || b2 < 0.05) continue;
        const Vec3 target =
            (1 - b1 - b2) * d.vertices[t[0]] + b1 * d.vertices[t[1]] + b2 * d.vertices[t[2]];
        const Vec3 from =
            3.0 * glm::normalize(Vec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5));
        const Vec3 dir = target - from;
        const auto reference = solidSpans(sphere24, from, dir, 1e-9);
        ASSERT_FALSE(reference.empty());
        for (PolygonMethod method : kLectureMethods) {
            const auto s = solidSpans(withMethod(sphere24, method), from, dir, 1e-9);
            EXPECT_TRUE(sameSpans(s, reference, 1e-12))
                << polygonMethodName(method) << " from " << str(from) << " to " << str(target);
        }
        ++compared;
    }
    EXPECT_GT(compared, 1000);
}

// The interpolated normals: Snyder's barycentric weights and Marchal's two steps are the same
// weights reached two ways, so the normals agree; at a cube's face (creases of 90 degrees)
// they are the face's own normal; at the apex of a low regular pyramid (faces 20 degrees
// apart at most, all averaged) the corner normal is +z by symmetry.
TEST(PolygonMethods, InterpolatedNormals) {
    const Polyhedron sphere24 = build(sphere(24, 12, 1.0));
    const auto& d = *sphere24.data;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0.05, 0.45);
    double worst = 0.0, flatGap = 0.0, smoothGap = 0.0;
    for (uint32_t i = 0; i < d.triangles.size() && i < 65535; ++i) {
        const auto& t = d.triangles[i];
        const double b1 = unit(random), b2 = unit(random);
        const Vec3 p =
            (1 - b1 - b2) * d.vertices[t[0]] + b1 * d.vertices[t[1]] + b2 * d.vertices[t[2]];
        const Vec3 snyder = withMethod(sphere24, PolygonMethod::Snyder).normal(p, uint16_t(i));
        const Vec3 marchal = withMethod(sphere24, PolygonMethod::Marchal).normal(p, uint16_t(i));
        worst = std::max(worst, glm::length(snyder - marchal));
        // The round sphere's normal at p's direction: the smooth normal is nearer to it.
        const Vec3 round = glm::normalize(p);
        flatGap += glm::length(sphere24.normal(p, uint16_t(i)) - round);
        smoothGap += glm::length(snyder - round);
    }
    EXPECT_LT(worst, 1e-13);
    EXPECT_LT(smoothGap, 0.5 * flatGap);

    const Polyhedron cube1 = build(cube(true));
    for (PolygonMethod method : kLectureMethods) {
        const Polyhedron p = withMethod(cube1, method);
        // Hit the x = 0 face near a corner: its triangles' corner normals are all -x.
        std::vector<Polyhedron::Crossing> c;
        p.crossings(Vec3(-1, 0.1, 0.05), Vec3(1, 0, 0), c);
        ASSERT_FALSE(c.empty());
        const Vec3 n = p.normal(Vec3(0, 0.1, 0.05), uint16_t(c[0].triangle));
        EXPECT_EQ(n, Vec3(-1, 0, 0)) << polygonMethodName(method) << ": " << str(n);
    }

    // A regular 8-sided pyramid, apex (0, 0, 0.2) over a unit circle: each face rises
    // atan(0.2 / cos(22.5 degrees)) = 12.2 degrees, so two faces turn 24.4 degrees from each
    // other at most, under the crease: the apex averages all eight.
    MeshInput pyramid;
    pyramid.points.push_back(Vec3(0, 0, 0.2));
    for (int k = 0; k < 8; ++k)
        pyramid.points.push_back(Vec3(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4), 0.0));
    for (uint32_t k = 0; k < 8; ++k) pyramid.faces.add({0, 1 + k, 1 + (k + 1) % 8});
    pyramid.faces.add({8, 7, 6, 5, 4, 3, 2, 1});
    const Polyhedron cone = withMethod(build(pyramid), PolygonMethod::Snyder);
    std::vector<Polyhedron::Crossing> c;
    cone.crossings(Vec3(0.01, 0.02, 1), Vec3(0, 0, -1), c);
    ASSERT_FALSE(c.empty());
    const Vec3 apex = cone.normal(Vec3(0, 0, 0.2), uint16_t(c[0].triangle));
    EXPECT_NEAR(apex.x, 0.0, 1e-15);
    EXPECT_NEAR(apex.y, 0.0, 1e-15);
    EXPECT_NEAR(apex.z, 1.0, 1e-15);
}

TEST(PolygonMethods, NamesRoundTrip) {
    for (PolygonMethod m :
         {PolygonMethod::Watertight, PolygonMethod::Snyder, PolygonMethod::Marchal})
        EXPECT_EQ(parsePolygonMethod(polygonMethodName(m)), m);
    EXPECT_FALSE(parsePolygonMethod("woop"));
}

}  // namespace
