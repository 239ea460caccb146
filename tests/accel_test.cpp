// The spatial structures of --accel (primitives/base/Accel.h), and the slab polyhedra of
// --bounds=slabs: every one answers every query exactly as the SAH BVH with boxes does (same
// spans, same hits, bit for bit) on thousands of seeded rays over several scenes, over a union's
// objects and over a mesh's faces; the uniform grid's walk visits the cells a hand-drawn ray
// crosses, in order; the lecture's hierarchies keep their invariants.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>

#include "bench/BenchScenes.h"
#include "csg/Scene.h"
#include "primitives/Polyhedron.h"
#include "primitives/base/Grid.h"
#include "primitives/base/WideBvh.h"
#include "tests/SeededRng.h"
#include "tests/TreeOracle.h"

namespace csg {
namespace {

Mat4 at(const Vec3& p) {
    return glm::translate(Mat4(1.0), p);
}

// Spheres of radius 0.2 .. 1 uniformly in a 40-unit cube.
NodePtr randomSpheres(int count) {
    testing::Rng rng(11);
    std::vector<NodePtr> parts;
    for (int i = 0; i < count; ++i) {
        const Vec3 c = rng.inBox(Vec3(0.0), Vec3(40.0));
        const double r = rng.uniform(0.2, 1.0);
        parts.push_back(transformed(at(c), leaf(Sphere{r})));
    }
    return uniteAll(parts);
}

// A difference or intersection of two random bounded primitives, turned.
NodePtr smallPart(std::mt19937_64& shapes, bool difference) {
    const NodePtr a = leaf(testing::randomPrimitive(shapes, false));
    const NodePtr b =
        transformed(testing::randomAffine(shapes), leaf(testing::randomPrimitive(shapes, false)));
    return transformed(testing::randomAffine(shapes),
                       difference ? subtract(a, b) : intersect(a, b));
}

// Most objects in five tight clusters, a few spread wide, some large: what defeats a uniform
// grid. The objects are small CSG parts.
NodePtr clustered(int count) {
    testing::Rng rng(12);
    std::mt19937_64 shapes(13);
    std::array<Vec3, 5> centres;
    for (Vec3& c : centres) c = rng.inBox(Vec3(-50.0), Vec3(50.0));
    std::vector<NodePtr> parts;
    for (int i = 0; i < count; ++i) {
        Vec3 c;
        double scale = 0.05;
        if (i % 50 == 0) {
            c = rng.inBox(Vec3(-60.0), Vec3(60.0));
            scale = i % 100 == 0 ? 8.0 : 0.5;
        } else {
            c = centres[static_cast<size_t>(rng.index(5))] + 2.0 * rng.inBall();
        }
        const NodePtr part = smallPart(shapes, i % 2 == 0);
        parts.push_back(transformed(at(c) * glm::scale(Mat4(1.0), Vec3(scale)), part));
    }
    return uniteAll(parts);
}

// A closed mesh (a UV sphere of the given segments) as a polyhedron leaf.
Polyhedron meshBall(int segments) {
    std::vector<Vec3> points;
    PolygonFaces faces;
    const int rings = segments / 2;
    for (int i = 0; i <= rings; ++i) {
        const double phi = glm::pi<double>() * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double theta = 2.0 * glm::pi<double>() * j / segments;
            points.emplace_back(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta),
                                std::cos(phi));
            if (i == 0 || i == rings) break;  // one point at a pole
        }
    }
    const auto index = [&](int i, int j) -> uint32_t {
        if (i == 0) return 0;
        if (i == rings) return static_cast<uint32_t>(points.size() - 1);
        return static_cast<uint32_t>(1 + (i - 1) * segments + (j % segments));
    };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = index(i, j), b = index(i, j + 1), c = index(i + 1, j),
                           d = index(i + 1, j + 1);
            if (i > 0) {
                for (uint32_t k : {a, c, b}) faces.corners.push_back(k);
                faces.closeFace();
            }
            if (i + 1 < rings) {
                for (uint32_t k : {b, c, d}) faces.corners.push_back(k);
                faces.closeFace();
            }
        }
    }
    Polyhedron mesh = Polyhedron::make(points, faces);
    EXPECT_EQ(mesh.invalidReason(), nullptr);
    return mesh;
}

// Meshes as the objects of a union: 300 placed copies of a 24 x 12 UV sphere, cut by boxes.
NodePtr meshes() {
    testing::Rng rng(14);
    const NodePtr ball = leaf(meshBall(24));
    std::vector<NodePtr> parts;
    for (int i = 0; i < 300; ++i) {
        const Vec3 c = rng.inBox(Vec3(0.0), Vec3(20.0));
        const NodePtr part = i % 3 == 0 ? subtract(ball, leaf(Box{Vec3(0.0), Vec3(2.0)})) : ball;
        parts.push_back(transformed(at(c), part));
    }
    return uniteAll(parts);
}

bool sameHit(const Hit& a, const Hit& b) {
    return std::memcmp(&a.t, &b.t, sizeof a.t) == 0 && a.leaf == b.leaf && a.face == b.face &&
           a.flipped == b.flipped && a.sheet == b.sheet;
}

// Rays from around the scene's box toward points in it (and some from inside, some along an
// axis, some with a finite range), the same for every structure.
std::vector<Ray> raysFor(const Bounds3& box, int count) {
    testing::Rng rng(15);
    const Vec3 c = box.center(), e = box.extent();
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Ray ray;
        const Vec3 target = rng.inBox(box.lo, box.hi);
        if (i % 4 == 0) {
            ray.o = rng.inBox(box.lo, box.hi);  // from inside
            ray.d = rng.unit();
        } else {
            ray.o = c + 1.5 * glm::length(e) * rng.unit();
            ray.d = target - ray.o;
        }
        if (i % 10 == 1) {  // along an axis, through the target
            const int axis = rng.index(3);
            ray.d = Vec3(0.0);
            ray.d[axis] = rng.chance(0.5) ? 1.0 : -1.0;
            ray.o = target;
            ray.o[axis] = c[axis] - ray.d[axis] * e[axis];
        }
        if (i % 7 == 3) {
            ray.tmin = rng.uniform(0.0, 0.5);
            ray.tmax = rng.uniform(0.5, 1.5);
        }
        rays.push_back(ray);
    }
    return rays;
}

std::string spansText(std::span<const Span> spans) {
    std::ostringstream out;
    out.precision(17);
    for (const Span& s : spans)
        out << " [" << s.in.t << " leaf " << s.in.leaf << " face " << s.in.face << ", " << s.out.t
            << " leaf " << s.out.leaf << " face " << s.out.face << "]";
    return out.str();
}

// Every other structure, and Kay and Kajiya's slab polyhedra (CompileOptions::slabs) with two
// of them: a bound changes what is tested, never an answer.
struct Variant {
    const char* name;
    CompileOptions options;
};
const Variant kOthers[] = {{"median", {.accel = Accel::Median}},
                           {"goldsmith-salmon", {.accel = Accel::GoldsmithSalmon}},
                           {"grid", {.accel = Accel::Grid}},
                           {"nonuniform-grid", {.accel = Accel::NonUniformGrid}},
                           {"auto", {.accel = Accel::Auto}},
                           {"sah with slabs", {.slabs = true}},
                           {"grid with slabs", {.accel = Accel::Grid, .slabs = true}}};

// Every query of every ray against the SAH scene's answers.
// Rays aimed into `aim`, or into the scene's bounds when it is empty, then the `extra` ones.
void expectSameAnswers(const NodePtr& tree, int rayCount, Bounds3 aim = {},
                       const std::vector<Ray>& extra = {}) {
    const Scene sah = Scene::compile(tree);
    std::vector<Ray> rays = raysFor(aim.empty() ? sah.bounds() : aim, rayCount);
    rays.insert(rays.end(), extra.begin(), extra.end());
    QueryContext sahContext, context;
    size_t hits = 0;
    for (const Variant& variant : kOthers) {
        SCOPED_TRACE(variant.name);
        const Scene other = Scene::compile(tree, variant.options);
        int failures = 0;
        for (size_t i = 0; i < rays.size() && failures < 5; ++i) {
            const Ray& ray = rays[i];
            const std::vector<Span> want(sah.spans(ray, sahContext).begin(),
                                         sah.spans(ray, sahContext).end());
            const std::span<const Span> got = other.spans(ray, context);
            bool sameSpans = got.size() == want.size();
            for (size_t k = 0; sameSpans && k < got.size(); ++k)
                sameSpans = sameHit(got[k].in, want[k].in) && sameHit(got[k].out, want[k].out);
            const std::optional<Hit> wantHit = sah.closest(ray, sahContext);
            const std::optional<Hit> gotHit = other.closest(ray, context);
            const bool sameClosest = wantHit.has_value() == gotHit.has_value() &&
                                     (!wantHit || sameHit(*wantHit, *gotHit));
            const bool sameOccluded = sah.occluded(ray, sahContext) == other.occluded(ray, context);
            hits += wantHit.has_value();
            if (!sameSpans || !sameClosest || !sameOccluded) {
                ++failures;
                ADD_FAILURE() << "ray " << i << ": o (" << ray.o.x << ", " << ray.o.y << ", "
                              << ray.o.z << ") d (" << ray.d.x << ", " << ray.d.y << ", " << ray.d.z
                              << ") [" << ray.tmin << ", " << ray.tmax << "]"
                              << (sameSpans ? "" : " spans differ")
                              << (sameClosest ? "" : " closest differs")
                              << (sameOccluded ? "" : " occluded differs") << "; closest t "
                              << (wantHit ? wantHit->t : -1.0) << " leaf "
                              << (wantHit ? wantHit->leaf : 0u) << " vs "
                              << (gotHit ? gotHit->t : -1.0) << " leaf "
                              << (gotHit ? gotHit->leaf : 0u) << spansText(want) << " vs"
                              << spansText(got);
            }
        }
    }
    EXPECT_GT(hits, static_cast<size_t>(rayCount) / 10);  // the rays did meet the scene
}

TEST(Accel, RandomSpheresSameAsSah) {
    expectSameAnswers(randomSpheres(5000), 4000);
}

// auto takes the uniform grid for a large evenly spread union (a grid's memory, well below the
// BVH's), the SAH BVH for a small one and a clustered one.
TEST(Accel, AutoPicksTheGridWhereObjectsSpreadEvenly) {
    const auto bytes = [](const NodePtr& tree, Accel accel) {
        return Scene::compile(tree, {.accel = accel}).structureBytes();
    };
    const NodePtr spread = randomSpheres(5000);
    EXPECT_EQ(bytes(spread, Accel::Auto), bytes(spread, Accel::Grid));
    const NodePtr few = randomSpheres(1000);
    EXPECT_EQ(bytes(few, Accel::Auto), bytes(few, Accel::Sah));
    const NodePtr gathered = clustered(5000);
    EXPECT_EQ(bytes(gathered, Accel::Auto), bytes(gathered, Accel::Sah));
}

TEST(Accel, ClusteredSameAsSah) {
    expectSameAnswers(clustered(2000), 4000);
}

TEST(Accel, CsgGridSameAsSah) {
    expectSameAnswers(bench::emblemGridTree(), 4000);
}

TEST(Accel, MeshesSameAsSah) {
    expectSameAnswers(meshes(), 3000);
}

// A mesh's faces under each structure (auto keeps the SAH there): a 96-segment ball (9 000
// triangles) and the benchmarks' terrain at 5 000 triangles, each one leaf, with lines
// along the axes through the terrain's vertices (on even x and y) and along its edges, where a
// walk that rounds into the wrong cell or tests a triangle twice would lose or pair a crossing.
TEST(Accel, MeshFacesSameAsSah) {
    const Polyhedron ball = meshBall(96);
    const NodePtr landLeaf = bench::terrainMeshTree(5000);
    const Polyhedron& land = std::get<Polyhedron>(landLeaf->primitive);
    ASSERT_EQ(land.invalidReason(), nullptr);
    EXPECT_TRUE(land.edges().manifold());
    for (const Accel accel :
         {Accel::Median, Accel::GoldsmithSalmon, Accel::Grid, Accel::NonUniformGrid}) {
        const std::shared_ptr<const MeshStructure> s = Polyhedron::organize(*land.data, accel);
        ASSERT_NE(s, nullptr);
        EXPECT_EQ(s->accel, accel);
    }
    EXPECT_EQ(Polyhedron::organize(*land.data, Accel::Auto), nullptr);

    // Compile gives the leaf the structure asked for, and spans() walks it: a grid whose cells
    // list nothing finds no crossing.
    EXPECT_NE(Scene::compile(landLeaf, {.accel = Accel::Grid}).structureBytes(),
              Scene::compile(landLeaf).structureBytes());
    const Ray down{Vec3(10.3, 20.6, 9.0), Vec3(0.0, 0.0, -1.0)};
    Polyhedron blind = land;
    auto empty = std::make_shared<MeshStructure>(*Polyhedron::organize(*land.data, Accel::Grid));
    std::fill(empty->grid.cellStart.begin(), empty->grid.cellStart.end(), 0u);
    blind.structure = empty;
    LocalSpans seen, unseen;
    land.spans(down.o, down.d, seen);
    blind.spans(down.o, down.d, unseen);
    EXPECT_EQ(seen.count, 1);
    EXPECT_EQ(unseen.count, 0);

    expectSameAnswers(leaf(ball), 3000);
    std::vector<Ray> along;
    testing::Rng rng(18);
    for (int k = 0; k < 400; ++k) {
        const double x = 2.0 * rng.index(51), y = 2.0 * rng.index(51);
        const double half = k % 3 == 0 ? 1.0 : 0.0;  // through vertices, or along edges
        along.push_back({Vec3(x + half, y, 9.0), Vec3(0.0, 0.0, -1.0)});
        along.push_back({Vec3(-1.0, y + half, rng.uniform(0.0, 4.0)), Vec3(1.0, 0.0, 0.0)});
        along.push_back({Vec3(x, -1.0, rng.uniform(0.0, 4.0)), Vec3(0.0, 1.0, 0.0)});
        along.push_back({Vec3(x, y, 9.0), Vec3(2.0, 2.0, -1.0)});  // diagonally, through corners
    }
    expectSameAnswers(landLeaf, 3000, {}, along);
}

// Meshes that are whole objects are asked by closest() and any() for their first span only
// (Polyhedron's horizon walk): both still answer as the whole span list does, for rays from
// outside, from inside a mesh and starting late, over the terrain, placed balls and a cut one.
TEST(Accel, MeshObjectsAnswerClosestAndOccludedAsTheirSpans) {
    testing::Rng rng(19);
    const NodePtr ball = leaf(meshBall(48));
    std::vector<NodePtr> parts = {bench::terrainMeshTree(5000)};
    for (int i = 0; i < 12; ++i) {
        const Vec3 c = rng.inBox(Vec3(10.0, 10.0, 4.0), Vec3(90.0, 90.0, 8.0));
        const NodePtr placed = transformed(at(c) * glm::scale(Mat4(1.0), Vec3(3.0)), ball);
        parts.push_back(i % 4 == 0 ? subtract(placed, leaf(Box{c, c + Vec3(4.0)})) : placed);
    }
    const Scene scene = Scene::compile(uniteAll(parts));
    std::vector<Ray> rays = raysFor(scene.bounds(), 6000);
    // Every third ray starts late (most rays reach their aim at t = 1).
    for (size_t i = 0; i < rays.size(); i += 3)
        if (std::isinf(rays[i].tmax)) rays[i].tmin = rng.uniform(0.2, 0.8);
    QueryContext ctx;
    int hits = 0, inside = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& ray = rays[i];
        const std::vector<Span> spans(scene.spans(ray, ctx).begin(), scene.spans(ray, ctx).end());
        std::optional<Hit> want;
        for (const Span& s : spans) {
            if (s.in.isSurface() || s.out.isSurface()) {
                want = s.in.isSurface() ? s.in : s.out;
                break;
            }
        }
        const std::optional<Hit> got = scene.closest(ray, ctx);
        ASSERT_EQ(got.has_value(), want.has_value()) << "ray " << i;
        if (want) {
            EXPECT_TRUE(sameHit(*got, *want))
                << "ray " << i << ": t " << got->t << " vs " << want->t << spansText(spans);
            ++hits;
            inside += !spans[0].in.isSurface();
        }
        ASSERT_EQ(scene.occluded(ray, ctx), !spans.empty()) << "ray " << i;
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(inside, 100);  // rays that start inside a mesh, which take the whole list
}

// Nested unions: each object a union of six small parts (a structure of its own), and a
// difference whose right operand is such a union.
TEST(Accel, NestedUnionsSameAsSah) {
    std::mt19937_64 shapes(16);
    std::vector<NodePtr> parts;
    testing::Rng rng(17);
    for (int i = 0; i < 400; ++i) {
        std::vector<NodePtr> group;
        for (int k = 0; k < 6; ++k) group.push_back(smallPart(shapes, k % 2 == 0));
        const NodePtr object = i % 4 == 0
                                   ? subtract(leaf(Box{Vec3(-1.5), Vec3(1.5)}), uniteAll(group))
                                   : uniteAll(group);
        parts.push_back(transformed(at(rng.inBox(Vec3(0.0), Vec3(30.0))), object));
    }
    expectSameAnswers(uniteAll(parts), 3000);
}

TEST(Accel, NamesRoundTrip) {
    for (size_t i = 0; i < kAccelNames.size(); ++i) {
        const Accel accel = static_cast<Accel>(i);
        EXPECT_EQ(parseAccel(accelName(accel)), accel);
    }
    EXPECT_EQ(parseAccel("octree"), std::nullopt);
}

// A 4 x 4 x 1 grid of unit cells over [0, 4] x [0, 4] x [0, 1].
UniformGrid fourByFour() {
    UniformGrid g;
    g.box = {Vec3(0.0), Vec3(4.0, 4.0, 1.0)};
    g.res[0] = 4;
    g.res[1] = 4;
    g.res[2] = 1;
    g.cellSize = Vec3(1.0);
    g.invCellSize = Vec3(1.0);
    return g;
}

// The cells (x, y) a ray from o along d visits from its entry at tIn, and their entry t.
std::vector<std::array<double, 3>> walk(const UniformGrid& g, const Vec3& o, const Vec3& d,
                                        double tIn) {
    const Vec3 invD = 1.0 / d;
    GridCursor cursor(g, o, d, invD, tIn);
    std::vector<std::array<double, 3>> cells{{double(cursor.cell[0]), double(cursor.cell[1]), tIn}};
    double t;
    while (cursor.advance(g, o, invD, t))
        cells.push_back({double(cursor.cell[0]), double(cursor.cell[1]), t});
    return cells;
}

// From (0.5, 0.25) along (1, 0.5): crosses x = 1 at t = 0.5 (y = 0.5), y = 1 at t = 1.5
// (x = 2), x = 2 at the same t = 1.5 (the tie goes to x first, then y), x = 3 at t = 2.5
// (y = 1.5), y = 2 at t = 3.5 (x = 4: the grid's edge, so the walk ends there).
TEST(GridWalk, ShallowSlopeWithACornerTie) {
    const auto cells = walk(fourByFour(), {0.5, 0.25, 0.5}, {1.0, 0.5, 0.0}, 0.0);
    const std::vector<std::array<double, 3>> want = {
        {0, 0, 0.0}, {1, 0, 0.5}, {2, 0, 1.5}, {2, 1, 1.5}, {3, 1, 2.5}};
    EXPECT_EQ(cells, want);
}

// Entering from outside at (4, 3.5) going (-1, -1) from o = (5, 4.5) at t = 1: the cell
// (3, 3) (x = 4 is the grid's edge, clamped in), then y = 3 at t = 1.5, x = 3 at t = 2,
// y = 2 at 2.5, x = 2 at 3, y = 1 at 3.5, x = 1 at 4 (at (1, 0.5)); next would be y = 0 at
// 4.5, out through the bottom, so the walk ends in (0, 0).
TEST(GridWalk, DiagonalFromOutside) {
    const auto cells = walk(fourByFour(), {5.0, 4.5, 0.5}, {-1.0, -1.0, 0.0}, 1.0);
    const std::vector<std::array<double, 3>> want = {
        {3, 3, 1.0}, {3, 2, 1.5}, {2, 2, 2.0}, {2, 1, 2.5}, {1, 1, 3.0}, {1, 0, 3.5}, {0, 0, 4.0}};
    EXPECT_EQ(cells, want);
}

// Along an axis: d = (0, 1, 0), x stays in cell 2 (o.x = 2.5); y faces at t = 1, 2, 3.
TEST(GridWalk, AlongAnAxis) {
    const auto cells = walk(fourByFour(), {2.5, 0.0, 0.5}, {0.0, 1.0, 0.0}, 0.0);
    const std::vector<std::array<double, 3>> want = {
        {2, 0, 0.0}, {2, 1, 1.0}, {2, 2, 2.0}, {2, 3, 3.0}};
    EXPECT_EQ(cells, want);
}

// The grid lists each box in every cell its widened box touches, and a box ending on a face
// in both cells beside it.
TEST(GridBuild, ListsBoxesInEveryCellTheyTouch) {
    std::vector<Bounds3> boxes = {{Vec3(0.0), Vec3(1.0)}, {Vec3(9.0), Vec3(10.0)}};
    for (int i = 0; i < 14; ++i) boxes.push_back({Vec3(5.0), Vec3(5.0)});
    const UniformGrid g = buildUniformGrid(boxes, 100);
    size_t listed0 = 0, listed1 = 0;
    for (uint32_t item : g.items) {
        listed0 += item == 100;
        listed1 += item == 101;
    }
    EXPECT_GE(listed0, 1u);
    EXPECT_GE(listed1, 1u);
    const HalvingGrid h = buildHalvingGrid(boxes, 0);
    EXPECT_FALSE(h.cells[0].leaf);
}

// Each hierarchy holds every item exactly once and every node's box holds its slots' boxes.
TEST(Hierarchies, EveryItemOnceInsideItsBoxes) {
    testing::Rng rng(18);
    std::vector<Bounds3> boxes(5000);
    for (Bounds3& b : boxes) {
        const Vec3 c = rng.inBox(Vec3(0.0), Vec3(100.0));
        b = {c - Vec3(rng.uniform(0.0, 2.0)), c + Vec3(rng.uniform(0.0, 2.0))};
    }
    for (BvhMethod method : {BvhMethod::Sah, BvhMethod::Median, BvhMethod::GoldsmithSalmon}) {
        std::vector<uint32_t> order;
        std::vector<BvhNode> nodes;
        const uint32_t root =
            buildWideBvh(boxes, order, 0, {.maxLeafItems = 1, .method = method}, nodes);
        std::vector<int> seen(boxes.size(), 0);
        std::vector<uint32_t> stack{root};
        while (!stack.empty()) {
            const BvhNode& n = nodes[stack.back()];
            stack.pop_back();
            for (int k = 0; k < n.slots; ++k) {
                const Bounds3 slot{{n.boxes.lo[0][k], n.boxes.lo[1][k], n.boxes.lo[2][k]},
                                   {n.boxes.hi[0][k], n.boxes.hi[1][k], n.boxes.hi[2][k]}};
                if (n.leafCount[k] == 0) {
                    stack.push_back(n.slot[k]);
                    continue;
                }
                for (uint32_t i = 0; i < n.leafCount[k]; ++i) {
                    const uint32_t item = order[n.slot[k] + i];
                    ++seen[item];
                    EXPECT_TRUE(slot.contains(boxes[item]));
                }
            }
        }
        for (int s : seen) ASSERT_EQ(s, 1);
    }
}

// A large SAH build on several threads (BvhBuildOptions::threads) is node for node the one a
// single thread makes, with the same leaf order: over boxes spread about, and over boxes most
// of which share one centre (the build's halving fallback, inside the parts and above them).
TEST(Hierarchies, SahOnThreadsIsTheSerialTree) {
    testing::Rng rng(21);
    std::vector<Bounds3> spread(150000), stacked(90000);
    for (Bounds3& b : spread) {
        const Vec3 c = rng.inBox(Vec3(0.0), Vec3(100.0));
        b = {c - Vec3(rng.uniform(0.0, 1.0)), c + Vec3(rng.uniform(0.0, 1.0))};
    }
    for (size_t i = 0; i < stacked.size(); ++i) {
        const Vec3 c = i % 3 == 0 ? rng.inBox(Vec3(0.0), Vec3(10.0)) : Vec3(5.0);
        stacked[i] = {c - Vec3(0.5), c + Vec3(0.5)};
    }
    for (const std::vector<Bounds3>* boxes : {&spread, &stacked}) {
        const auto build = [&](int threads, std::vector<uint32_t>& order) {
            std::vector<BvhNode> nodes;
            const BvhBuildOptions options{.maxLeafItems = 2, .threads = threads};
            EXPECT_EQ(buildWideBvh(*boxes, order, 7, options, nodes), 0u);
            return nodes;
        };
        std::vector<uint32_t> serialOrder;
        const std::vector<BvhNode> serial = build(1, serialOrder);
        ASSERT_GT(serial.size(), 1000u);
        for (int threads : {2, 3}) {
            std::vector<uint32_t> order;
            const std::vector<BvhNode> nodes = build(threads, order);
            ASSERT_EQ(nodes.size(), serial.size()) << threads << " threads";
            EXPECT_EQ(order, serialOrder) << threads << " threads";
            for (size_t i = 0; i < nodes.size(); ++i) {
                const BvhNode &a = nodes[i], &b = serial[i];
                bool same = a.slots == b.slots;
                for (int k = 0; k < 4; ++k) {
                    same = same && a.slot[k] == b.slot[k] && a.leafCount[k] == b.leafCount[k];
                    for (int axis = 0; axis < 3; ++axis)
                        same = same && a.boxes.lo[axis][k] == b.boxes.lo[axis][k] &&
                               a.boxes.hi[axis][k] == b.boxes.hi[axis][k];
                }
                for (int octant = 0; octant < 8; ++octant)
                    same = same && a.order[octant] == b.order[octant];
                ASSERT_TRUE(same) << "node " << i << ", " << threads << " threads";
            }
        }
    }
}

}  // namespace
}  // namespace csg
