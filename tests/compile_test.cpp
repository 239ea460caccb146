// Compiling trees: transforms flattened into leaves, unions flattened, bounds, pruning, BVH.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "csg/Scene.h"
#include "tests/SeededRng.h"

namespace csg {
namespace {

Mat4 translation(double x, double y, double z) {
    return glm::translate(Mat4(1.0), Vec3(x, y, z));
}

TEST(Compile, TransformsAreFlattenedIntoEachLeaf) {
    const Mat4 outer = translation(1, 2, 3);
    const Mat4 inner = glm::scale(Mat4(1.0), Vec3(2, 3, 4));
    const NodePtr tree =
        transformed(outer, unite(transformed(inner, leaf(Sphere{1})), leaf(Box{})));
    const Scene scene = Scene::compile(tree);
    ASSERT_EQ(scene.leafCount(), 2u);
    const Mat4 want = outer * inner;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_DOUBLE_EQ(scene.leafWorldFromLocal(0)[c][r], want[c][r]);
    // The scaled, translated sphere's tight bounds: centre (1,2,3), radii (2,3,4).
    const Bounds3 b = scene.bounds();
    EXPECT_DOUBLE_EQ(b.lo.x, -1.0);
    EXPECT_DOUBLE_EQ(b.lo.y, -1.0);
    EXPECT_DOUBLE_EQ(b.lo.z, -1.0);
    EXPECT_DOUBLE_EQ(b.hi.z, 7.0);
}

TEST(Compile, SingularAndNonFiniteTransformsAreErrorsNamingTheNode) {
    Tags tags{42, 0};
    auto flat = std::make_shared<Node>(*leaf(Sphere{1}, tags));
    flat->parentFromNode = glm::scale(Mat4(1.0), Vec3(1, 0, 1));
    try {
        Scene::compile(unite(leaf(Box{}), flat));
        FAIL() << "a scale(0) must not compile";
    } catch (const CompileError& e) {
        EXPECT_EQ(e.source, 42u);
        EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos);
    }
    Mat4 nan(1.0);
    nan[3][0] = std::nan("");
    EXPECT_THROW(Scene::compile(transformed(nan, leaf(Sphere{1}))), CompileError);
    // Two scales that are each fine but whose product underflows to singular.
    const Mat4 tiny = glm::scale(Mat4(1.0), Vec3(1e-120));
    EXPECT_THROW(Scene::compile(transformed(tiny, transformed(tiny, leaf(Sphere{1})))),
                 CompileError);
}

TEST(Compile, PrimitiveParametersOutOfTheirDomainAreErrors) {
    for (const Primitive& bad : std::initializer_list<Primitive>{
             Sphere{0.0}, Sphere{-1.0}, Sphere{std::nan("")}, Box{Vec3(0), Vec3(1, 0, 1)},
             Cylinder{0.0, 1, 1}, Cylinder{1, 0, 0}, Cylinder{1, -1, 1}, HalfSpace{Vec3(0), 1.0},
             Torus{1.0, 1.0}, Torus{1.0, 0.0}}) {
        try {
            Scene::compile(unite(leaf(Sphere{1}), leaf(bad, {7, 0})));
            ADD_FAILURE() << "primitive " << bad.index() << " compiled";
        } catch (const CompileError& e) {
            EXPECT_EQ(e.source, 7u);
        }
    }
    EXPECT_NO_THROW(Scene::compile(leaf(Torus{1.0, 0.999})));
}

TEST(Compile, EmptyOverlapPrunesAndDisjointCutIsDropped) {
    const NodePtr far = transformed(translation(10, 0, 0), leaf(Sphere{1}));
    const Scene pruned = Scene::compile(intersect(leaf(Sphere{1}), far));
    EXPECT_EQ(pruned.leafCount(), 2u);  // leaves are compiled, but no node refers to them
    EXPECT_TRUE(pruned.bounds().empty());
    QueryContext ctx;
    EXPECT_TRUE(pruned.spans(Ray{{-20, 0, 0}, {1, 0, 0}}, ctx).empty());

    const Scene cut = Scene::compile(subtract(leaf(Sphere{1}), far));
    const auto spans = cut.spans(Ray{{-20, 0, 0}, {1, 0, 0}}, ctx);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_DOUBLE_EQ(spans[0].in.t, 19.0);
    EXPECT_DOUBLE_EQ(spans[0].out.t, 21.0);
}

TEST(Compile, EmptySceneAnswersNothing) {
    const Scene scene = Scene::compile(nullptr);
    QueryContext ctx;
    const Ray ray{{0, 0, -5}, {0, 0, 1}};
    EXPECT_TRUE(scene.spans(ray, ctx).empty());
    EXPECT_FALSE(scene.closest(ray, ctx));
    EXPECT_FALSE(scene.occluded(ray, ctx));
    EXPECT_TRUE(scene.bounds().empty());
}

// Operands whose box test the parent's test already implies are not tested again: in A - B
// with B's box holding A's, a ray tests the root's box and the difference's only, and still
// gets the difference's spans. A is the unit sphere; B a box 1.6 x 1.6 x 2.4 turned 45 degrees
// about z, whose bounds (+-1.13, +-1.13, +-1.2) hold the sphere's but which leaves the parts of
// the sphere beyond 0.8 from its faces.
TEST(Compile, CutOperandsWhoseTestIsImpliedAreNotTestedAgain) {
    const Mat4 turn = glm::rotate(Mat4(1.0), 0.25 * 3.141592653589793, Vec3(0, 0, 1));
    const NodePtr cut = transformed(turn, leaf(Box{Vec3(-0.8, -0.8, -1.2), Vec3(0.8, 0.8, 1.2)}));
    const Scene scene = Scene::compile(subtract(leaf(Sphere{1}), cut));
    // Along z through the point at u = (x + y) / sqrt 2 = 0.9, v = 0: outside the box, inside
    // the sphere for |z| <= sqrt(1 - 0.81).
    const double xy = 0.9 / std::sqrt(2.0), half = std::sqrt(1.0 - 0.81);
    QueryContext ctx;
    const auto spans = scene.spans(Ray{{xy, xy, -5}, {0, 0, 1}}, ctx);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].in.t, 5.0 - half, 1e-12);
    EXPECT_NEAR(spans[0].out.t, 5.0 + half, 1e-12);
    EXPECT_EQ(ctx.stats.nodeVisits, 2u);  // the root union wrapping the part, the difference
    // The sphere is solved; the box's own frame shows the ray missing it, so it is not.
    EXPECT_EQ(ctx.stats.primitiveTests, 1u);
    // Through the middle the box removes the whole chord.
    EXPECT_TRUE(scene.spans(Ray{{0, 0, -5}, {0, 0, 1}}, ctx).empty());
}

// Kay and Kajiya's slabs (CompileOptions::slabs) around a unit cube turned 45 degrees about z:
// its box is |x|, |y| <= sqrt(1/2), |z| <= 1/2; along n = (1, 1, 1) the cube reaches
// sqrt(1/2) + 1/2 = 1.207, its box sqrt(2) + 1/2 = 1.914. A ray along (1, -1, 0) (in the planes
// n . x = const) at x + y = 0.8, z = 0.45 crosses the box (|x|, |y| <= 0.707 for
// |s| <= 0.307) at n . x = 1.25, outside the slab: the slabs cull it before the cube's frame is
// entered, where without them the leaf's own local box rejects it. A ray through the middle
// is not culled and meets the cube from u = (x - y) / sqrt 2 = -1/2 to 1/2.
TEST(Compile, SlabPolyhedraCullWhatTheBoxLetsThrough) {
    const Mat4 turn = glm::rotate(Mat4(1.0), 0.25 * 3.141592653589793, Vec3(0, 0, 1));
    const NodePtr cube = transformed(turn, leaf(Box{Vec3(-0.5), Vec3(0.5)}));
    const Scene boxes = Scene::compile(cube);
    const Scene slabs = Scene::compile(cube, {.slabs = true});
    const Ray past{{0.4 - 5.0, 0.4 + 5.0, 0.45}, {1, -1, 0}};
    QueryContext withBoxes, withSlabs;
    EXPECT_TRUE(boxes.spans(past, withBoxes).empty());
    EXPECT_TRUE(slabs.spans(past, withSlabs).empty());
    EXPECT_EQ(withBoxes.stats.slabCulls, 0u);
    EXPECT_EQ(withSlabs.stats.slabCulls, 1u);
    const Ray through{{-5.0, 5.0, 0.0}, {1, -1, 0}};
    const auto spans = slabs.spans(through, withSlabs);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].in.t, 5.0 - 0.5 / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(spans[0].out.t, 5.0 + 0.5 / std::sqrt(2.0), 1e-12);
    EXPECT_EQ(withSlabs.stats.slabCulls, 1u);
}

// A union of n spheres on a grid: node visits per ray must grow like log n, not n.
double visitsPerRay(int side) {
    std::vector<NodePtr> parts;
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            for (int k = 0; k < side; ++k)
                parts.push_back(
                    transformed(translation(3.0 * i, 3.0 * j, 3.0 * k), leaf(Sphere{1})));
    const Scene scene = Scene::compile(uniteAll(parts));
    QueryContext ctx;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 3.0 * side);
    constexpr int kRays = 2000;
    for (int r = 0; r < kRays; ++r) {
        // Rays along -z through random points above the grid's top layer.
        scene.closest(Ray{{u(rng), u(rng), 3.0 * side + 5}, {0, 0, -1}}, ctx);
    }
    return static_cast<double>(ctx.stats.nodeVisits) / kRays;
}

TEST(Compile, BvhMakesNodeVisitsLogarithmic) {
    const double small = visitsPerRay(10);  // 10^3 spheres
    const double large = visitsPerRay(46);  // ~10^5 spheres
    // Linear growth would be ~100x. A ray down a column meets ~n^(1/3) sphere boxes before
    // its first hit at worst, so allow 8x, and bound the count by a multiple of log2 n.
    EXPECT_LT(large, 8 * small) << small << " vs " << large;
    EXPECT_LT(large, 15 * std::log2(46.0 * 46 * 46)) << large;
    // Not vacuous: every ray visits at least the root union's node, and a tree over ~100
    // times the spheres is at least one level deeper (log4 of 100 is 3.3 levels of the 4-wide
    // BVH) for the rays that reach a sphere, so the mean grows. A count that stayed zero, or a
    // walk that ignored the tree's depth, fails here.
    EXPECT_GE(small, 1.0) << small;
    EXPECT_GT(large, small) << small << " vs " << large;
}

// The box tests the BVH makes redundant are skipped, and only those. A skipped test only saves
// work (a wrong flag still finds the same spans), so the counts are what pins the rules. Four unit
// cubes centred at x = 0, 3, 6, 9: the binned SAH splits them 2 | 2 (cost 0.5 + (9 + 9) / 21
// against 0.5 + (3 + 45) / 21 for 1 | 3; half areas 3, 9, 15, 21 for 1 to 4 cubes), then each pair
// 1 | 1 (0.5 + 6 / 9 < 2), so the binary tree is root -> {A: cubes 0, 1; B: cubes 2, 3} with one
// cube per leaf, and the 4-wide BVH is one node whose four slots are the cubes. A ray along +y
// through a cube's centre meets only that cube's slot. spans() through cube 0: the root union's
// own box is not tested (the BVH's slots lie in it); the four slots are (one wide test, 4
// visits); cube 0's own box is not tested again (its slot's box is the same): cube 0 is solved,
// 1 test. Testing either box again would make 5 visits.
TEST(Compile, BoxTestsTheBvhImpliesAreSkipped) {
    std::vector<NodePtr> cubes;
    for (int i = 0; i < 4; ++i)
        cubes.push_back(transformed(translation(3.0 * i, 0, 0),
                                    leaf(Box{Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)})));
    const Scene scene = Scene::compile(uniteAll(cubes));
    const auto along = [](double x) { return Ray{{x, -5, 0}, {0, 1, 0}}; };

    QueryContext ctx;
    const auto spans = scene.spans(along(0.0), ctx);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_EQ(spans[0].in.t, 4.5);
    EXPECT_EQ(spans[0].out.t, 5.5);
    EXPECT_EQ(ctx.stats.nodeVisits, 4u);
    EXPECT_EQ(ctx.stats.primitiveTests, 1u);

    // occluded() with an object cache. First, empty: the four slots are tested (4 visits),
    // cube 0 is solved (1 test) and answers; the search stops and caches it.
    ObjectCache cache;
    ctx.stats = {};
    EXPECT_TRUE(scene.occluded(along(0.0), ctx, cache));
    EXPECT_EQ(ctx.stats.nodeVisits, 4u);
    EXPECT_EQ(ctx.stats.primitiveTests, 1u);
    // Through cube 1: the cached cube 0 is tried outside the BVH walk, so its own box is tested
    // (1 visit, a miss: not solved); then the four slots: 5 visits, cube 1 solved. Skipping
    // cube 0's test would make 4 visits.
    ctx.stats = {};
    EXPECT_TRUE(scene.occluded(along(3.0), ctx, cache));
    EXPECT_EQ(ctx.stats.nodeVisits, 5u);
    EXPECT_EQ(ctx.stats.primitiveTests, 1u);
}

// Children whose centres coincide cannot be split: four concentric spheres share one leaf slot,
// the BVH's only one. Its box is the largest sphere's, so each child's own box is still tested:
// moved off the origin (each leaf in a frame of its own), 1 slot and 4 children, 5 visits, 4
// spheres solved, one span from the largest. At the origin, in the world's frame, a child's
// box is the one evalLeaf clips the ray to first, so it is not tested before: 1 visit, the
// same solves and span.
TEST(Compile, ConcentricChildrenShareOneLeafSlot) {
    for (const Vec3 centre : {Vec3(1, 2, 3), Vec3(0)}) {
        SCOPED_TRACE(centre.x);
        std::vector<NodePtr> spheres;
        for (int r = 1; r <= 4; ++r)
            spheres.push_back(
                transformed(glm::translate(Mat4(1.0), centre), leaf(Sphere{double(r)})));
        const Scene scene = Scene::compile(uniteAll(spheres));
        QueryContext ctx;
        const Vec3 o = centre + Vec3(0, 0, -10);
        const auto spans = scene.spans(Ray{o, {0, 0, 1}}, ctx);
        ASSERT_EQ(spans.size(), 1u);
        EXPECT_EQ(spans[0].in.t, 6.0);
        EXPECT_EQ(spans[0].out.t, 14.0);
        EXPECT_EQ(ctx.stats.nodeVisits, centre == Vec3(0) ? 1u : 5u);
        EXPECT_EQ(ctx.stats.primitiveTests, 4u);
        // Outside the smaller spheres' boxes only the largest is solved.
        ctx.stats = {};
        EXPECT_TRUE(scene.occluded(Ray{o + Vec3(3.5, 0, 0), {0, 0, 1}}, ctx));
        EXPECT_EQ(ctx.stats.primitiveTests, 1u);
    }
}

// The 4-wide BVH walk against every part on its own: a union of 400 overlapping parts (several
// levels of wide nodes, slots of nodes and of parts mixed) answers each ray as the parts do
// together: spans() is inside exactly where some part's spans are, closest() is the nearest of
// the parts' first hits (rays starting outside every part), occluded() is whether any part is
// met. Rays start anywhere: outside, inside parts, and late (tmin > 0).
TEST(Compile, WideBvhWalkAnswersAsThePartsDoTogether) {
    testing::Rng rng(400);
    std::vector<NodePtr> parts;
    std::vector<Scene> alone;
    for (int i = 0; i < 400; ++i) {
        const Vec3 at = rng.inBox(Vec3(-10.0), Vec3(10.0));
        const double size = rng.uniform(0.2, 1.5);
        const NodePtr shape = rng.chance(0.5)
                                  ? leaf(Sphere{size})
                                  : leaf(Box{Vec3(-size), Vec3(size, 0.5 * size, 2 * size)});
        parts.push_back(transformed(glm::translate(Mat4(1.0), at), shape));
        alone.push_back(Scene::compile(parts.back()));
    }
    const Scene scene = Scene::compile(uniteAll(parts));
    QueryContext ctx, partCtx;
    int hits = 0, inside = 0;
    for (int r = 0; r < 3000; ++r) {
        const Vec3 o = rng.inBox(Vec3(-14.0), Vec3(14.0));
        const Vec3 d = glm::normalize(rng.inBox(Vec3(-1.0), Vec3(1.0)) + Vec3(0.0, 0.0, 1e-3));
        const Ray ray{o, d, r % 3 == 0 ? rng.uniform(0.0, 5.0) : 0.0, 40.0};
        const std::vector<Span> all(scene.spans(ray, ctx).begin(), scene.spans(ray, ctx).end());
        // spans(): membership at sampled t, away from every end.
        std::vector<std::vector<Span>> each;
        for (const Scene& part : alone) {
            const auto s = part.spans(ray, partCtx);
            each.emplace_back(s.begin(), s.end());
        }
        const auto in = [](const std::vector<Span>& spans, double t) {
            for (const Span& s : spans)
                if (t >= s.in.t && t <= s.out.t) return true;
            return false;
        };
        const auto nearEnd = [](const std::vector<Span>& spans, double t) {
            for (const Span& s : spans)
                if (std::abs(t - s.in.t) < 1e-9 || std::abs(t - s.out.t) < 1e-9) return true;
            return false;
        };
        for (int k = 0; k < 64; ++k) {
            const double t = ray.tmin + (ray.tmax - ray.tmin) * (k + 0.5) / 64;
            bool want = false, ambiguous = nearEnd(all, t);
            for (const auto& s : each) {
                want = want || in(s, t);
                ambiguous = ambiguous || nearEnd(s, t);
            }
            if (!ambiguous) {
                ASSERT_EQ(in(all, t), want) << "ray " << r << " t " << t;
            }
        }
        // occluded(): any part met.
        bool anyMet = false, startsInside = false;
        double nearest = kInfinity;
        for (const auto& s : each) {
            anyMet = anyMet || !s.empty();
            if (s.empty()) continue;
            if (!s[0].in.isSurface()) startsInside = true;
            nearest = std::min(nearest, s[0].in.t);
        }
        ASSERT_EQ(scene.occluded(ray, ctx), anyMet) << "ray " << r;
        // closest(): the nearest part's first hit, for rays that start outside every part.
        const std::optional<Hit> got = scene.closest(ray, ctx);
        inside += startsInside;
        if (startsInside) continue;
        ASSERT_EQ(got.has_value(), anyMet) << "ray " << r;
        if (got) {
            ++hits;
            EXPECT_EQ(got->t, nearest) << "ray " << r;
        }
    }
    EXPECT_GT(hits, 600);  // many rays meet a part, and some start inside one
    EXPECT_GT(inside, 50);
}

// A map with exact 0 and +-1 entries: column j is sign[j] times axis to[j], then a shift.
Mat4 axisMap(std::array<int, 3> to, std::array<double, 3> sign, Vec3 shift) {
    Mat4 m(0.0);
    for (int j = 0; j < 3; ++j) m[j][to[j]] = sign[j];
    m[3] = Vec4(shift, 1.0);
    return m;
}

// Leaves turned by exact axis permutations (rotate by 90 degrees, mirror, center=true) share
// their part's frame in the ray loop, reached by a swizzle instead of their own matrix. The
// oracle is point classification (Scene::inside), which maps every point through each leaf's
// own inverted matrix: every span's middle must be inside the part and every gap's outside.
// Cones (r1 != r2) and a mirror make a wrong axis or sign show.
TEST(Compile, LeavesTurnedByAxisPermutationsMatchTheirOwnMatrices) {
    const Cylinder cone{2.0, 0.18, 0.34};
    // Each cone centred on the origin (center = true) and turned onto another axis.
    const NodePtr cut = uniteAll(std::vector<NodePtr>{
        transformed(axisMap({2, 1, 0}, {1, 1, -1}, Vec3(0)) * translation(0, 0, -1), leaf(cone)),
        transformed(axisMap({0, 2, 1}, {1, -1, 1}, Vec3(0.05, 0, 0)) * translation(0, 0, -1),
                    leaf(cone)),
        transformed(axisMap({1, 0, 2}, {-1, 1, 1}, Vec3(0)) * translation(0, 0, -1), leaf(cone)),
    });
    const NodePtr part =
        subtract(intersect(leaf(Box{Vec3(-0.5), Vec3(0.5)}), leaf(Sphere{0.68})), cut);
    const Mat4 general = translation(0.3, -0.2, 0.1) *
                         glm::rotate(Mat4(1.0), 0.7, glm::normalize(Vec3(1, 2, 3))) *
                         glm::scale(Mat4(1.0), Vec3(1.3, 0.8, 1.1));
    const Scene scene = Scene::compile(transformed(general, part));

    QueryContext ctx;
    testing::Rng rng(11);
    int cylinderEnds = 0, checked = 0;
    for (int r = 0; r < 4000; ++r) {
        const Vec3 target = Vec3(0.3, -0.2, 0.1) + 0.7 * rng.inBox(Vec3(-1.0), Vec3(1.0));
        const Vec3 origin = 6.0 * rng.unit();
        const Ray ray{origin, target - origin};
        const auto spans = scene.spans(ray, ctx);
        double gapStart = 0.0;
        for (const Span& s : spans) {
            cylinderEnds += (s.in.leaf >= 2) + (s.out.leaf >= 2);
            if (s.out.t - s.in.t > 1e-6) {
                EXPECT_TRUE(scene.inside(ray.at(0.5 * (s.in.t + s.out.t)))) << r;
                ++checked;
            }
            if (s.in.t - gapStart > 1e-6) {
                EXPECT_FALSE(scene.inside(ray.at(0.5 * (gapStart + s.in.t)))) << r;
            }
            gapStart = s.out.t;
        }
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(cylinderEnds, 1000);  // the permuted leaves were met, not just the box and sphere
}

}  // namespace
}  // namespace csg
