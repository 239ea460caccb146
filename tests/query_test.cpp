// The three queries against the point-membership oracle on seeded random trees.
#include <gtest/gtest.h>

#include "csg/Scene.h"
#include "tests/SeededRng.h"
#include "tests/TreeOracle.h"

namespace csg {
namespace {

using testing::insideTree;
using testing::randomTree;

bool member(std::span<const Span> spans, double t) {
    for (const Span& s : spans)
        if (t >= s.in.t && t <= s.out.t) return true;
    return false;
}

// Distance from t to the nearest span end.
double distanceToEnd(std::span<const Span> spans, double t) {
    double best = kInfinity;
    for (const Span& s : spans)
        best = std::min({best, std::abs(t - s.in.t), std::abs(t - s.out.t)});
    return best;
}

struct RandomRays {
    std::mt19937_64 rng;
    explicit RandomRays(uint64_t seed) : rng(seed) {}
    // Rays from a sphere of radius 8 toward random points of [-2, 2]^3, a quarter of them
    // starting inside that cube; |d| varies so t is not always a distance.
    Ray next() {
        std::uniform_real_distribution<double> u(-1.0, 1.0), len(0.1, 10.0);
        const Vec3 target(2 * u(rng), 2 * u(rng), 2 * u(rng));
        Vec3 o(u(rng), u(rng), u(rng));
        o = std::uniform_int_distribution<int>(0, 3)(rng) == 0
                ? 2.0 * o
                : 8.0 * o / std::max(glm::length(o), 1e-9);
        Vec3 d = target - o;
        if (glm::length(d) < 1e-6) d = Vec3(0, 0, 1);
        d = glm::normalize(d) * len(rng);
        return Ray{o, d, 0.0, 20.0 / glm::length(d)};
    }
};

// Every span list agrees with the oracle at sampled points: in the middle of spans and gaps,
// just inside and outside each end, and at random points along the ray.
TEST(Query, SpansAgreeWithPointMembershipOnRandomTrees) {
    constexpr int kTrees = 200, kRaysPerTree = 500;  // 10^5 rays
    std::mt19937_64 rng(2024);
    QueryContext ctx;
    int nonEmpty = 0;
    for (int tree = 0; tree < kTrees; ++tree) {
        const NodePtr root = randomTree(rng, 6);
        const Scene scene = Scene::compile(root);
        RandomRays rays(tree);
        for (int r = 0; r < kRaysPerTree; ++r) {
            const Ray ray = rays.next();
            const auto spans = scene.spans(ray, ctx);
            nonEmpty += !spans.empty();
            // Sample t where the classification is unambiguous: away from every end by a
            // margin far above the coincidence tolerance.
            const double margin = 1e-6 * ray.tmax;
            std::vector<double> ts;
            for (size_t i = 0; i < spans.size(); ++i) {
                ASSERT_LE(spans[i].in.t, spans[i].out.t);
                ASSERT_GE(spans[i].in.t, ray.tmin);
                ASSERT_LE(spans[i].out.t, ray.tmax);
                if (i > 0) {
                    ASSERT_LT(spans[i - 1].out.t, spans[i].in.t);
                }
                ts.push_back(0.5 * (spans[i].in.t + spans[i].out.t));
                if (i + 1 < spans.size()) ts.push_back(0.5 * (spans[i].out.t + spans[i + 1].in.t));
                for (double e : {spans[i].in.t, spans[i].out.t})
                    for (double side : {-1e-4, 1e-4}) ts.push_back(e + side * ray.tmax);
            }
            std::uniform_real_distribution<double> along(ray.tmin, ray.tmax);
            for (int k = 0; k < 8; ++k) ts.push_back(along(rng));
            for (double t : ts) {
                if (t < ray.tmin || t > ray.tmax || distanceToEnd(spans, t) < margin) continue;
                ASSERT_EQ(member(spans, t), insideTree(root, ray.at(t)))
                    << "tree " << tree << " ray " << r << " t " << t;
            }
        }
    }
    // The test is only meaningful if the random trees are not mostly empty.
    EXPECT_GT(nonEmpty, kTrees * kRaysPerTree / 5);
}

// closest() is the first surface end of spans(); occluded() is "spans is not empty", with or
// without an ObjectCache (kept across the tree's rays, so it is often stale). Every other ray
// starts late (tmin > 0, as a secondary ray does), often inside a solid or inside a
// difference's left operand, where closest()'s and any()'s shortcuts must still agree.
TEST(Query, ClosestAndOccludedAgreeWithSpans) {
    std::mt19937_64 rng(77);
    testing::Rng late(78);
    QueryContext ctx;
    int cachedAnswers = 0;
    for (int tree = 0; tree < 100; ++tree) {
        const Scene scene = Scene::compile(randomTree(rng, 6));
        ObjectCache cache;
        RandomRays rays(1000 + tree);
        for (int r = 0; r < 300; ++r) {
            Ray ray = rays.next();
            if (r % 2 == 1) ray.tmin = late.uniform(0.3, 0.7) * ray.tmax;
            const auto spans = scene.spans(ray, ctx);
            std::optional<Hit> want;
            for (const Span& s : spans) {
                if (s.in.isSurface()) {
                    want = s.in;
                    break;
                }
                if (s.out.isSurface()) {
                    want = s.out;
                    break;
                }
            }
            const bool wantOccluded = !spans.empty();
            const std::optional<Hit> got = scene.closest(ray, ctx);
            ASSERT_EQ(got.has_value(), want.has_value()) << "tree " << tree << " ray " << r;
            if (want) {
                EXPECT_NEAR(got->t, want->t, 1e-9 * ray.tmax);
                EXPECT_EQ(got->leaf, want->leaf);
            }
            ASSERT_EQ(scene.occluded(ray, ctx), wantOccluded) << "tree " << tree << " ray " << r;
            const uint32_t before = cache.node;
            ASSERT_EQ(scene.occluded(ray, ctx, cache), wantOccluded)
                << "tree " << tree << " ray " << r << " (cached)";
            if (wantOccluded && before == cache.node) ++cachedAnswers;
        }
    }
    EXPECT_GT(cachedAnswers, 1000);  // the cached object did answer, not only the BVH walk
}

// Coincident faces: copies of one box (and a taller one sharing its bottom) in one union. A
// line through their common faces enters and leaves at one t in every copy, and whatever the
// order the union's BVH visits them in along that line, closest() and spans() name the lowest
// leaf there (SpanList.h's tie-break), so neighbouring pixels cannot flip between the copies'
// colours.
TEST(Query, CoincidentFacesNameTheLowestLeafInEveryQuery) {
    std::vector<NodePtr> copies;
    for (int k = 0; k < 6; ++k) copies.push_back(leaf(Box{Vec3(-1.0), Vec3(1.0)}));
    copies.push_back(leaf(Box{Vec3(-1.0), Vec3(1.0, 1.0, 3.0)}));
    const Scene scene = Scene::compile(uniteAll(copies));
    QueryContext ctx;
    RandomRays rays(91);
    int hits = 0;
    for (int r = 0; r < 2000; ++r) {
        const Ray ray = rays.next();
        const auto spans = scene.spans(ray, ctx);
        if (spans.empty() || !spans[0].in.isSurface()) continue;
        const Hit entry = spans[0].in;  // the view lives in ctx until the next query
        const std::optional<Hit> hit = scene.closest(ray, ctx);
        ASSERT_TRUE(hit);
        // The lowest leaf whose box has the entry point on its surface: 0 unless the line
        // enters through the tall box's own top part (z > 1).
        const Vec3 p = ray.o + hit->t * ray.d;
        const uint32_t want = p.z > 1.0 + 1e-9 ? 6u : 0u;
        EXPECT_EQ(hit->leaf, want) << "ray " << r;
        EXPECT_EQ(entry.leaf, want) << "ray " << r;
        ++hits;
    }
    EXPECT_GT(hits, 200);
}

// A ray that starts inside a top-level object leaves the scene where the root union's first
// span ends: at that object's exit when nothing else is near it (closest() then merges no other
// object's list), and past it where another object covers the exit or touches it. Sphere A
// (leaf 0) at the origin, B (leaf 1) overlapping it along +x, C (leaf 2) touching A's surface
// at y = 1 from outside, and a floor (leaf 3) under all of them.
TEST(Query, RaysStartingInsideLeaveWhereTheUnionEnds) {
    const auto at = [](double x, double y, double z, NodePtr n) {
        return transformed(glm::translate(Mat4(1.0), Vec3(x, y, z)), std::move(n));
    };
    const Scene scene = Scene::compile(
        uniteAll({leaf(Sphere{1.0}), at(1.5, 0, 0, leaf(Sphere{1.0})),
                  at(0, 2, 0, leaf(Sphere{1.0})), leaf(HalfSpace{Vec3(0, 0, 1), -5.0})}));
    QueryContext ctx;
    struct Case {
        Vec3 d;
        double t;
        uint32_t leaf;
    };
    // From A's centre: along -x A's own exit; along +x B covers A's exit, so B's far side;
    // along +y C begins where A ends (the union closes the gap), so C's far side; along -z
    // A's exit, 4 short of the floor.
    const Case cases[] = {{Vec3(-1, 0, 0), 1.0, 0},
                          {Vec3(1, 0, 0), 2.5, 1},
                          {Vec3(0, 1, 0), 3.0, 2},
                          {Vec3(0, 0, -1), 1.0, 0}};
    for (int k = 0; k < 4; ++k) {
        const Case& c = cases[k];
        const std::optional<Hit> hit = scene.closest(Ray{Vec3(0.0), c.d, 0.0, 100.0}, ctx);
        ASSERT_TRUE(hit) << "case " << k;
        EXPECT_NEAR(hit->t, c.t, 1e-12) << "case " << k;
        EXPECT_EQ(hit->leaf, c.leaf) << "case " << k;
    }
    // Rays from random points inside A against the whole list's answer.
    testing::Rng rng(2029);
    int byOthers = 0;
    for (int r = 0; r < 10000; ++r) {
        const Vec3 o = 0.99 * rng.inBall();
        const Ray ray{o, rng.unit(), 0.0, 100.0};
        const auto spans = scene.spans(ray, ctx);
        ASSERT_FALSE(spans.empty());
        ASSERT_FALSE(spans[0].in.isSurface());
        const Hit want = spans[0].out;
        byOthers += want.leaf != 0;
        const std::optional<Hit> got = scene.closest(ray, ctx);
        ASSERT_TRUE(got) << "ray " << r;
        EXPECT_EQ(got->t, want.t) << "ray " << r;
        EXPECT_EQ(got->leaf, want.leaf) << "ray " << r;
    }
    EXPECT_GT(byOthers, 1000);  // B or C decided often, not only A's own exit
}

// The same for the parts of bench/scenes/torus_glass: rays refracted into a torus that is one
// leaf (its first span solved for where it begins only, firstOnly, so its end may come early),
// and into a torus cut by a box (the difference's first span, whose end closest() hands on
// when the box is clear of it), over a floor. Origins inside either torus, random directions.
TEST(Query, RaysStartingInsideATorusLeaveWhereItsSpansEnd) {
    const NodePtr cutTorus =
        transformed(glm::translate(Mat4(1.0), Vec3(7, 0, 0)),
                    subtract(leaf(Torus{2.0, 1.0}), leaf(Box{Vec3(-4, -4, 0.2), Vec3(4, 0, 2)})));
    const Scene scene = Scene::compile(
        uniteAll({leaf(Torus{2.0, 1.0}), cutTorus, leaf(HalfSpace{Vec3(0, 0, 1), -1.0})}));
    ASSERT_TRUE(std::holds_alternative<Box>(scene.leafPrimitive(2)));
    QueryContext ctx;
    testing::Rng rng(2030);
    int byBox = 0;
    for (int r = 0; r < 20000; ++r) {
        const bool cut = r % 2 == 1;
        Vec3 p;
        do {
            p = rng.inBox(Vec3(-3, -3, -1), Vec3(3, 3, 1));
        } while (!Torus{2.0, 1.0}.inside(p) ||
                 (cut && p.y < 0 && p.z > 0.2));  // inside the part, not in the cut
        const Ray ray{cut ? p + Vec3(7, 0, 0) : p, rng.unit(), 0.0, 100.0};
        const auto spans = scene.spans(ray, ctx);
        ASSERT_FALSE(spans.empty());
        ASSERT_FALSE(spans[0].in.isSurface());
        const Hit want = spans[0].out;
        byBox += cut && want.leaf == 2;
        const std::optional<Hit> got = scene.closest(ray, ctx);
        ASSERT_TRUE(got) << "ray " << r;
        EXPECT_EQ(got->t, want.t) << "ray " << r;
        EXPECT_EQ(got->leaf, want.leaf) << "ray " << r;
    }
    EXPECT_GT(byBox, 500);  // rays leaving through the cut's faces, not only the tube
}

// Normals returned for hits are unit, finite and face the outside of the solid.
TEST(Query, SurfaceNormalsPointOutOfTheSolid) {
    std::mt19937_64 rng(5);
    QueryContext ctx;
    int rightWay = 0, wrongWay = 0;
    for (int tree = 0; tree < 100; ++tree) {
        const NodePtr root = randomTree(rng, 5);
        const Scene scene = Scene::compile(root);
        RandomRays rays(500 + tree);
        for (int r = 0; r < 400; ++r) {
            const Ray ray = rays.next();
            for (const Span& s : scene.spans(ray, ctx)) {
                for (const Hit& h : {s.in, s.out}) {
                    if (!h.isSurface()) continue;
                    const SurfacePoint sp = scene.surface(ray, h);
                    ASSERT_NEAR(glm::length(sp.normal), 1.0, 1e-9);
                    // Step along the normal: outside, and against it: inside, unless another
                    // surface is within reach (an edge or a thin wall).
                    const double eps = 1e-5;
                    const bool out = insideTree(root, sp.point + eps * sp.normal);
                    const bool in = insideTree(root, sp.point - eps * sp.normal);
                    rightWay += !out && in;
                    wrongWay += out && !in;
                }
            }
        }
    }
    // Most hits are away from edges and thin walls, where the steps are unambiguous.
    EXPECT_GT(rightWay, 10000);
    EXPECT_LT(wrongWay, rightWay / 1000 + 1);
}

// A difference whose left operand sticks out of every box of its right operand is answered
// without solving the right one (tol::kUncoveredPieceSlacks), but only where the merge would
// keep what sticks out: the unit cube minus itself moved by `gap` along x, hit along x. A gap
// of 1e-12 leaves a sliver the coincidence rule drops (no hit, nothing occluded); 1e-6 leaves
// a span that starts at the cube's own face x = 0. Both with the right operand alone and as
// one child of a short union (each child's box counts then).
TEST(Query, DifferenceAnsweredFromBoxesOnlyWhereTheMergeKeepsTheRest) {
    QueryContext ctx;
    const Box unit{Vec3(0.0), Vec3(1.0)};
    for (const double gap : {1e-12, 1e-6}) {
        const NodePtr moved =
            transformed(glm::translate(Mat4(1.0), Vec3(gap, 0.0, 0.0)), leaf(unit));
        const NodePtr far =
            transformed(glm::translate(Mat4(1.0), Vec3(0.5, 0.5, 4.0)), leaf(Sphere{0.25}));
        for (const NodePtr& right : {moved, unite(moved, far)}) {
            const Scene scene = Scene::compile(subtract(leaf(unit), right));
            const Ray ray{Vec3(-5.0, 0.5, 0.5), Vec3(1.0, 0.0, 0.0), 0.0, 100.0};
            const bool kept = gap > 1e-9;
            ObjectCache cache;
            EXPECT_EQ(scene.occluded(ray, ctx), kept) << "gap " << gap;
            EXPECT_EQ(scene.occluded(ray, ctx, cache), kept) << "gap " << gap;
            const std::optional<Hit> hit = scene.closest(ray, ctx);
            ASSERT_EQ(hit.has_value(), kept) << "gap " << gap;
            if (kept) {
                EXPECT_EQ(hit->t, 5.0);
                EXPECT_FALSE(hit->flipped);  // the cube's own face, not the cut's
            }
        }
    }
}

// A sphere placed by a similarity bounds the intersections and differences it is the left
// operand of with a ball that rejects lines before any leaf is solved (CompiledNode::ball).
// It must never reject a line that meets the sphere, however nearly tangent, at any scale:
// parts (sphere(r) n cube) - a small central ball, turned, mirrored, scaled by 10^-3..10^3
// and moved at random, hit by lines that pass r (1 - 1e-7) from the centre (chord half-length
// ~4.5e-4 r) and missed by lines r (1 + 1e-6) from it, which the ball rejects without a solve.
TEST(Query, BoundingBallRejectsOnlyLinesThatMissTheSphere) {
    testing::Rng rng(41);  // one value per statement or braced list: see SeededRng.h
    QueryContext ctx;
    for (int part = 0; part < 200; ++part) {
        const double scale = std::pow(10.0, rng.uniform(-3.0, 3.0)), r = 0.7;
        const Vec3 shift = rng.inBox(Vec3(-1.0), Vec3(1.0));
        Mat4 m = glm::translate(Mat4(1.0), scale * 5.0 * shift);
        const double angle = rng.uniform(0.0, 6.283185307179586);
        m = glm::rotate(m, angle, rng.unit());
        m = glm::scale(m, Vec3(part % 2 == 0 ? scale : -scale, scale, scale));
        const Scene scene = Scene::compile(
            transformed(m, subtract(intersect(leaf(Sphere{r}), leaf(Box{Vec3(-1.0), Vec3(1.0)})),
                                    leaf(Sphere{0.1}))));
        const Vec3 center(m[3]);
        const double radius = r * scale;
        for (int line = 0; line < 20; ++line) {
            // A direction, and a point at the wanted distance from the centre across it.
            const Vec3 direction = rng.unit();
            const Vec3 d = direction * std::pow(10.0, rng.uniform(-1.0, 1.0));
            const Vec3 across = glm::normalize(glm::cross(d, rng.unit()));
            for (const double factor : {1.0 - 1e-7, 1.0 + 1e-6}) {
                const Vec3 nearest = center + factor * radius * across;
                const double back = 10.0 * radius / glm::length(d);
                const Ray ray{nearest - back * d, d, 0.0, 2.0 * back};
                const bool meets = factor < 1.0;
                const uint64_t solves = ctx.stats.primitiveTests;
                const std::optional<Hit> hit = scene.closest(ray, ctx);
                ASSERT_EQ(hit.has_value(), meets) << "part " << part << " line " << line;
                if (meets) {
                    // Entry at back - half the chord, in units of t. Tolerance: the line's
                    // points are ~25 radii from the origin (shift up to 12 R, back 10 R), so
                    // placing it and mapping it to the sphere's frame moves it across by a few
                    // u * 25 R (u = 2^-53), and the discriminant r^2 - p^2 cancels ~100 r^2 to
                    // a few u * 100 r^2. A half chord h = 4.5e-4 R moves by R dp / h and
                    // d(disc) / 2h: each ~1e5 u R = 1e-11 R. 1e-9 R leaves a factor 100 and is
                    // 4e5 times smaller than h, so a hit at the closest-approach point fails.
                    const double halfChord = radius * std::sqrt(1.0 - factor * factor);
                    EXPECT_NEAR(hit->t, back - halfChord / glm::length(d),
                                1e-9 * radius / glm::length(d))
                        << "part " << part << " line " << line;
                } else {
                    EXPECT_EQ(ctx.stats.primitiveTests, solves) << "part " << part;
                }
                EXPECT_EQ(scene.occluded(ray, ctx), meets) << "part " << part << " line " << line;
            }
        }
    }
}

}  // namespace
}  // namespace csg
