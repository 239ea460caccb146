// The Whitted renderer (viewer/render/): the effects plan (which rays are cast, counted
// exactly), scale invariance of secondary-ray origins, refraction through a difference's cut
// face, the PNG it writes (decoded back with libpng), and Ctrl-C leaving no file.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>
#include <png.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "io/Evaluate.h"
#include "tests/SeededRng.h"
#include "viewer/render/Color.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/ImageOutput.h"
#include "viewer/render/Materials.h"
#include "viewer/render/Pattern.h"
#include "viewer/render/PngWriter.h"
#include "viewer/render/RenderCamera.h"
#include "viewer/render/SecondaryOrigin.h"
#include "viewer/render/TileRenderer.h"
#include "viewer/render/Tracer.h"

extern char** environ;

// Counts every heap allocation of the test binary, for the no-allocation-per-ray tests. GCC
// cannot see that the counting operator new is malloc, hence the pragma for the matching free.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#include "tests/CountingNew.h"
#include "tests/RenderScenes.h"
#include "tests/TempDir.h"

namespace viewer::render {
namespace {

namespace fs = std::filesystem;
using csg::testing::facingMirrors;
using csg::testing::planeUnder;

struct LoadedScene {
    io::Model model;
    csg::Scene scene;
};

LoadedScene load(const std::string& source) {
    io::EvaluateResult result = io::evaluateString(source, "render_test.scad");
    for (const io::Diagnostic& d : result.diagnostics) ADD_FAILURE() << d.message;
    LoadedScene loaded;
    if (!result.ok()) return loaded;
    loaded.model = std::move(*result.model);
    loaded.scene = csg::Scene::compile(loaded.model.root);
    return loaded;
}

struct Rendered {
    RenderResult result;
    EffectsPlan plan;
};

Rendered render(const LoadedScene& s, int width, int height, PlanSettings settings = {},
                int threads = 2, PixelStore store = PixelStore::LinearFloat, int aa = 1) {
    const render::Camera camera =
        s.model.camera ? *s.model.camera : frameBounds(s.scene, double(width) / height);
    Rendered r;
    r.plan = makeEffectsPlan(s.model, s.model.root.get(), s.scene, camera, settings);
    ImageSettings image;
    image.width = width;
    image.height = height;
    image.threads = threads;
    image.store = store;
    image.samplesPerAxis = aa;
    r.result =
        renderImage(s.scene, r.plan, RenderCamera(camera, width, height), image, nullptr, nullptr);
    return r;
}

// ---- the effects plan ----

const char* const kDiffuseScene = R"(
    light([5, -8, 10]);
    halfspace([0, 0, 1], 0);
    translate([0, 0, 1]) sphere(1);
    translate([2.5, 0, 0.75]) cube(1.5, center = true);
)";

TEST(EffectsPlan, DiffuseOnlySceneCastsNoReflectionOrRefractionRays) {
    const LoadedScene s = load(kDiffuseScene);
    const Rendered r = render(s, 40, 30);
    EXPECT_FALSE(r.plan.reflection);
    EXPECT_FALSE(r.plan.refraction);
    EXPECT_TRUE(r.plan.shadowRays);
    EXPECT_EQ(r.result.rays.primary, 40u * 30u);
    EXPECT_EQ(r.result.rays.reflection, 0u);
    EXPECT_EQ(r.result.rays.refraction, 0u);
    EXPECT_GT(r.result.rays.shadow, 0u);
}

TEST(EffectsPlan, ShadowsOffCastsNoShadowRays) {
    const LoadedScene s = load(kDiffuseScene);
    PlanSettings settings;
    settings.shadows = false;
    const Rendered r = render(s, 40, 30, settings);
    EXPECT_FALSE(r.plan.shadowRays);
    EXPECT_EQ(r.result.rays.shadow, 0u);

    // Per light: shadows=false on the only light has the same effect.
    std::string perLightSource = kDiffuseScene;
    const std::string light = "light([5, -8, 10]);";
    perLightSource.replace(perLightSource.find(light), light.size(),
                           "light([5, -8, 10], shadows=false);");
    const LoadedScene perLight = load(perLightSource);
    EXPECT_EQ(render(perLight, 40, 30).result.rays.shadow, 0u);
}

TEST(EffectsPlan, OneConvexSolidCastsNoShadowRays) {
    // A convex solid cannot shadow its own lit side, whatever the light.
    const LoadedScene s =
        load("light([3, -4, 5]); intersection() { sphere(1); cube(1.6, center = true); }");
    const Rendered r = render(s, 32, 32);
    EXPECT_TRUE(r.plan.convexScene);
    EXPECT_FALSE(r.plan.shadowRays);
    EXPECT_EQ(r.result.rays.shadow, 0u);
    EXPECT_GT(r.result.rays.primary, 0u);
}


TEST(EffectsPlan, MirrorReflectRaysFollowTheWeightThreshold) {
    constexpr uint64_t kPixels = 24 * 16;
    // 0.5^8 = 1/256 is still cast, 0.5^9 is not: 8 reflections per pixel.
    const Rendered half = render(load(facingMirrors(0.5)), 24, 16);
    EXPECT_TRUE(half.plan.reflection);
    EXPECT_FALSE(half.plan.direct);  // diffuse = specular = 0: no light terms, no shadow rays
    EXPECT_EQ(half.result.rays.primary, kPixels);
    EXPECT_EQ(half.result.rays.reflection, 8 * kPixels);
    EXPECT_EQ(half.result.rays.shadow, 0u);
    // 0.1^2 = 0.01 >= 1/256 > 0.1^3: two per pixel.
    EXPECT_EQ(render(load(facingMirrors(0.1)), 24, 16).result.rays.reflection, 2 * kPixels);
    // 0.001 < 1/256: the first reflection already weighs too little; none is cast.
    const Rendered faint = render(load(facingMirrors(0.001)), 24, 16);
    EXPECT_TRUE(faint.plan.reflection);
    EXPECT_EQ(faint.result.rays.reflection, 0u);
    // --max-depth cuts before the weight rule when it is smaller.
    PlanSettings shallow;
    shallow.maxDepth = 3;
    EXPECT_EQ(render(load(facingMirrors(0.5)), 24, 16, shallow).result.rays.reflection,
              3 * kPixels);
    // A lower threshold lets more through: 0.5^10 >= 2^-10.
    PlanSettings fine;
    fine.minWeight = 1.0 / 1024.0;
    EXPECT_EQ(render(load(facingMirrors(0.5)), 24, 16, fine).result.rays.reflection, 10 * kPixels);
}

TEST(EffectsPlan, UnusedMaterialsDoNotTurnEffectsOn) {
    // The glass material exists in the table but no leaf uses it... as it is never
    // instantiated, only the default material is in use.
    const LoadedScene s = load("light([3, -4, 5]); sphere(1); translate([3, 0, 0]) sphere(1);");
    const Rendered r = render(s, 32, 24);
    EXPECT_FALSE(r.plan.refraction);
    EXPECT_FALSE(r.plan.reflection);
    EXPECT_TRUE(r.plan.specular);  // render::Material's default has specular 0.2
}

// ---- secondary-ray origins ----

// A ray leaving a hit point (outward for reflection, inward for refraction) must never find
// the surface it leaves again, at any scale and from far-away origins.
TEST(SecondaryOrigin, NeverReHitsTheSurfaceItLeaves) {
    std::mt19937_64 rng(20240604);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const double scale : {1e-4, 1.0, 1e4}) {
        const LoadedScene s = load("translate([0.3, -0.2, 0.1]) sphere(1.3);");
        const LoadedScene scaled =
            load("scale(" + std::to_string(scale) + ") translate([0.3, -0.2, 0.1]) sphere(1.3);");
        csg::QueryContext ctx;
        int hits = 0;
        for (int i = 0; i < 4000; ++i) {
            const double far = std::pow(10.0, 1.0 + 5.0 * (unit(rng) + 1.0) / 2.0);
            const csg::Vec3 from =
                scale * far * glm::normalize(csg::Vec3(unit(rng), unit(rng), unit(rng)));
            const csg::Vec3 target =
                scale * (csg::Vec3(0.3, -0.2, 0.1) + csg::Vec3(unit(rng), unit(rng), unit(rng)));
            const csg::Ray ray{from, target - from, 0.0, csg::kInfinity};
            const std::optional<csg::Hit> hit = scaled.scene.closest(ray, ctx);
            if (!hit) continue;
            ++hits;
            const csg::SurfacePoint sp = scaled.scene.surface(ray, *hit);
            const csg::Vec3 error = hitPointError(ray, hit->t);
            const csg::Vec3 dir = glm::normalize(ray.d);
            const csg::Vec3 out = dir - 2.0 * glm::dot(dir, sp.normal) * sp.normal;
            const csg::Ray reflected{offsetRayOrigin(sp.point, error, sp.normal, out), out, 0.0,
                                     csg::kInfinity};
            EXPECT_FALSE(scaled.scene.closest(reflected, ctx)) << "scale " << scale << " ray " << i;
            // Inward: the next surface is the far side of the sphere, left (not entered).
            const csg::Ray inward{offsetRayOrigin(sp.point, error, sp.normal, dir), dir, 0.0,
                                  csg::kInfinity};
            const std::optional<csg::Hit> exit = scaled.scene.closest(inward, ctx);
            ASSERT_TRUE(exit) << "scale " << scale << " ray " << i;
            const csg::SurfacePoint exitPoint = scaled.scene.surface(inward, *exit);
            EXPECT_GT(glm::dot(inward.d, exitPoint.normal), 0.0) << "scale " << scale;
        }
        EXPECT_GT(hits, 1000);
        (void)s;
    }
}

// The same scene at 1e-4, 1 and 1e4 (camera and lights scaled with it) renders the same
// image: no shadow acne or self-hit speckles appear at any scale.
std::string scaledScene(double scale) {
    return "scale(" + std::to_string(scale) + ") {\n" + R"(
      camera(eye=[7, -9, 5], center=[0.5, 0, 0.8], up=[0, 0, 1], fov=40);
      light([6, -4, 9]);
      light([-6, -6, 4], color=[0.4, 0.4, 0.5]);
      halfspace([0, 0, 1], 0);
      translate([0, 0, 1]) sphere(1);
      material(diffuse=0.1, specular=0.6, shininess=80, reflect=0.6)
        translate([2.2, 1.0, 0.8]) sphere(0.8);
      material(ambient=0, diffuse=0.05, specular=0.5, shininess=200, transmit=0.85, ior=1.5)
        translate([-1.6, -1.2, 0.7]) difference() {
          cube(1.4, center = true);
          cylinder(h = 2, r = 0.35, center = true);
        }
      translate([0.5, 2.5, 0]) rotate([0, 0, 30]) cube([2, 0.4, 2.2]);
    })";
}

TEST(ScaleInvariance, SameImageAt1eMinus4And1And1e4) {
    const int w = 96, h = 72;
    std::vector<render::Rgb8Image> images;
    for (const double scale : {1e-4, 1.0, 1e4}) {
        const Rendered r = render(load(scaledScene(scale)), w, h);
        EXPECT_GT(r.result.rays.shadow, 0u);
        EXPECT_GT(r.result.rays.reflection, 0u);
        EXPECT_GT(r.result.rays.refraction, 0u);
        images.push_back(encodeSrgb(r.result.image));
    }
    for (int k : {0, 2}) {
        int differing = 0;
        for (size_t p = 0; p < images[1].pixels.size(); p += 3) {
            int worst = 0;
            for (int c = 0; c < 3; ++c)
                worst = std::max(
                    worst, std::abs(int(images[k].pixels[p + c]) - int(images[1].pixels[p + c])));
            differing += worst > 2;
        }
        // Silhouette pixels may round differently; acne would be hundreds of pixels.
        EXPECT_LE(differing, w * h / 500) << "scale " << (k == 0 ? "1e-4" : "1e4");
    }
}

// ---- refraction through a difference ----

const char* const kCutGlass = R"(
    material(ambient=0, diffuse=0, specular=0, transmit=1, ior=1.5)
      difference() {
        cube(2, center = true);
        cylinder(h = 4, r = 0.5, center = true);
      })";

TEST(Refraction, ARayInsideCutGlassLeavesThroughTheCutFace) {
    const LoadedScene s = load(kCutGlass);
    const EffectsPlan plan =
        makeEffectsPlan(s.model, s.model.root.get(), s.scene, render::Camera{}, {});
    ASSERT_TRUE(plan.refraction);
    Tracer tracer(s.scene, plan);
    PathLog log;
    tracer.log = &log;
    // Starts inside the glass, heading for the cylindrical hole.
    tracer.tracePrimary(csg::Ray{{-0.8, 0.0, 0.3}, {1.0, 0.0, 0.0}, 0.0, csg::kInfinity});
    ASSERT_GE(log.count, 3);
    const PathLog::Vertex& cut = log.vertices[0];
    EXPECT_FALSE(cut.entering) << "the ray leaves the glass into the hole";
    EXPECT_NEAR(cut.point.x, -0.5, 1e-12);
    EXPECT_NEAR(cut.point.y, 0.0, 1e-12);
    EXPECT_NEAR(cut.point.z, 0.3, 1e-12);
    EXPECT_NEAR(cut.normal.x, 1.0, 1e-12) << "the cut face's outward normal points into the hole";
    // Across the hole it enters the glass again, then leaves through the box's face.
    EXPECT_TRUE(log.vertices[1].entering);
    EXPECT_NEAR(log.vertices[1].point.x, 0.5, 1e-12);
    EXPECT_FALSE(log.vertices[2].entering);
    EXPECT_NEAR(log.vertices[2].point.x, 1.0, 1e-12);
    EXPECT_EQ(log.vertices[1].kind, RayKind::Refraction);
}

TEST(Refraction, ObliqueRayBendsBySnellsLawAtBothFacesOfTheCut) {
    const LoadedScene s = load(kCutGlass);
    const EffectsPlan plan =
        makeEffectsPlan(s.model, s.model.root.get(), s.scene, render::Camera{}, {});
    Tracer tracer(s.scene, plan);
    PathLog log;
    tracer.log = &log;
    // From outside, 30 degrees off the x axis in the xy plane, aimed to enter the face x = -1
    // at (-1, -0.1, 0).
    const double angle = 30.0 * M_PI / 180.0;
    const csg::Vec3 d(std::cos(angle), std::sin(angle), 0.0);
    tracer.tracePrimary(csg::Ray{csg::Vec3(-1.0, -0.1, 0.0) - 3.0 * d, d, 0.0, csg::kInfinity});
    ASSERT_GE(log.count, 2);
    EXPECT_TRUE(log.vertices[0].entering);
    EXPECT_NEAR(log.vertices[0].point.x, -1.0, 1e-12);
    // Inside: sin(t) = sin(30 deg) / 1.5.
    const double sinT = std::sin(angle) / 1.5;
    const csg::Vec3 inside(std::sqrt(1.0 - sinT * sinT), sinT, 0.0);
    // Expected exit at the cylinder x^2 + y^2 = 0.25: solve |p0 + s inside|^2 = r^2.
    const csg::Vec3 p0 = log.vertices[0].point;
    const double b = glm::dot(p0, inside), c = glm::dot(p0, p0) - 0.25;
    const double sHit = -b - std::sqrt(b * b - c);
    const csg::Vec3 expected = p0 + sHit * inside;
    EXPECT_FALSE(log.vertices[1].entering);
    EXPECT_NEAR(log.vertices[1].point.x, expected.x, 1e-9);
    EXPECT_NEAR(log.vertices[1].point.y, expected.y, 1e-9);
    EXPECT_NEAR(glm::length(csg::Vec3(log.vertices[1].point.x, log.vertices[1].point.y, 0)), 0.5,
                1e-9);
}

TEST(Refraction, TotalInternalReflectionKeepsTheRayInside) {
    // A ray inside glass (ior 1.5) meeting the face y = 1 at 60 degrees from its normal (the
    // critical angle is 41.8 degrees) is reflected: it next meets the face x = 1 at 30 degrees
    // and leaves there.
    const LoadedScene s = load(
        "material(ambient=0, diffuse=0, specular=0, transmit=1, ior=1.5) cube(2, center=true);");
    const EffectsPlan plan =
        makeEffectsPlan(s.model, s.model.root.get(), s.scene, render::Camera{}, {});
    Tracer tracer(s.scene, plan);
    PathLog log;
    tracer.log = &log;
    const double angle = 30.0 * M_PI / 180.0;
    tracer.tracePrimary(
        csg::Ray{{0.0, 0.5, 0.0}, {std::cos(angle), std::sin(angle), 0.0}, 0.0, csg::kInfinity});
    ASSERT_GE(log.count, 2);
    EXPECT_FALSE(log.vertices[0].entering);
    EXPECT_NEAR(log.vertices[0].point.y, 1.0, 1e-12);  // first the face y = 1
    EXPECT_FALSE(log.vertices[1].entering);            // reflected back inside to x = 1
    EXPECT_NEAR(log.vertices[1].point.x, 1.0, 1e-12);
}

// ---- light through glass: shadow rays filtered by transmissive solids ----

// A white plane z <= 0 (ambient 0, diffuse 1: a pixel is the light's cosine, nothing else),
// seen straight down by an orthographic camera at z = 1 whose view is 4 x 4 units; pixel
// (i, j) of an 8 x 8 image has its centre at x = -2 + (i + 0.5) / 2, y = 2 - (j + 0.5) / 2.
// The light is at (0, 0, 100). What hangs between z = 2 and z = 4 over x < 0 is behind the
// camera, so it is never seen, only crossed by shadow rays: a shadow ray from the plane at
// x < 0 toward the light stays at x < 0, one from x > 0 at x > 0. So the left half of the
// image (i < 4) is in the shadow of the slabs and the right half is not.
constexpr int kShadowImage = 8;

// Pixel (i, j) of a linear float render, i from the left, j from the top.
csg::Vec3 pixel(const RenderResult& r, int i, int j) {
    const float* p = &r.image.rgb[(size_t(j) * r.image.width + i) * 3];
    return {p[0], p[1], p[2]};
}


// A glass slab over x in [-10, 0], z in [z0, z0 + 1]: colour (sRGB) and transmit as given,
// no light of its own.
std::string glassSlab(double z0, const std::string& color, double transmit) {
    return "material(color = " + color +
           ", ambient = 0, diffuse = 0, specular = 0, transmit = " + std::to_string(transmit) +
           ") translate([-10, -10, " + std::to_string(z0) + "]) cube([10, 20, 1]);\n";
}

// The sRGB decoding of IEC 61966-2-1, written out here rather than taken from the renderer.
double linearFromSrgb(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Renders the plane under `slabs` and the bare plane, and checks every shadowed pixel (the left
// half) against the bare plane's times `transmission`, per channel, and the right half equal.
void expectShadowIsTransmission(const std::string& slabs, const csg::Vec3& transmission) {
    const Rendered bare = render(load(planeUnder("")), kShadowImage, kShadowImage);
    const Rendered under = render(load(planeUnder(slabs)), kShadowImage, kShadowImage);
    for (int j = 0; j < kShadowImage; ++j) {
        for (int i = 0; i < kShadowImage; ++i) {
            const csg::Vec3 lit = pixel(bare.result, i, j), seen = pixel(under.result, i, j);
            ASSERT_GT(lit.r, 0.5) << "the bare plane is lit everywhere";
            const csg::Vec3 want = i < kShadowImage / 2 ? transmission * lit : lit;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(seen[c], want[c], 1e-6)
                    << "pixel " << i << "," << j << " channel " << c;
        }
    }
}

TEST(LightThroughGlass, ShadowOfAGlassSlabIsItsTransmission) {
    // White glass passes transmit of the light in every channel.
    expectShadowIsTransmission(glassSlab(2, "[1, 1, 1]", 0.6), csg::Vec3(0.6));
}

TEST(LightThroughGlass, ColouredGlassFiltersEachChannelByItsColour) {
    // POV-Ray's filter: the light is multiplied by transmit times the glass's linear colour.
    const double t = 0.8;
    expectShadowIsTransmission(glassSlab(2, "[1, 0.5, 0.2]", t),
                               t * csg::Vec3(1.0, linearFromSrgb(0.5), linearFromSrgb(0.2)));
}

TEST(LightThroughGlass, AttenuatedOncePerSpanCrossed) {
    // Two slabs apart: two spans, the transmission twice.
    expectShadowIsTransmission(glassSlab(2, "[1, 1, 1]", 0.5) + glassSlab(3.5, "[1, 1, 1]", 0.5),
                               csg::Vec3(0.25));
    // Two slabs that touch are one solid, one span: once.
    expectShadowIsTransmission(glassSlab(2, "[1, 1, 1]", 0.5) + glassSlab(3, "[1, 1, 1]", 0.5),
                               csg::Vec3(0.5));
}

TEST(LightThroughGlass, OpaqueSolidsStillBlock) {
    // An opaque slab, alone or beside a glass one on the same shadow ray, leaves no light.
    const std::string opaque =
        "material(color = [1, 1, 1], ambient = 0, diffuse = 1, specular = 0) "
        "translate([-10, -10, 3.5]) cube([10, 20, 0.5]);\n";
    expectShadowIsTransmission(opaque, csg::Vec3(0.0));
    expectShadowIsTransmission(glassSlab(2, "[1, 1, 1]", 0.9) + opaque, csg::Vec3(0.0));
}

// ---- shading against its formulas ----

// The white plane of planeUnder() lit from (1, 0.5, 4) by a light of radiance 1, with
// diffuse 0.6, specular 0.3 and shininess 20, seen straight down (the view vector is +z
// everywhere), an opaque bar over x in [-1, 0] at z in [1.5, 2] (behind the camera) casting
// its shadow on the columns whose centres lie at x < -0.6. Each pixel is computed here from the formulas: Lambert's kd * albedo * (n . l)
// plus Blinn-Phong's ks * (n . h)^shininess with h = normalize(l + v), or 0 in the shadow
// (ambient 0). Tolerance: the image holds floats (relative 2^-24 of values below 1) and the
// hit point is exact to ~1e-16, so 1e-6 is a margin of ~16 over the float rounding; a missing
// term or a Phong (r . v) highlight instead of Blinn's is off by more than 1e-3.
TEST(Shading, LambertAndBlinnPhongPixelsAndAShadowedOne) {
    const std::string source =
        "camera(eye = [0, 0, 1], center = [0, 0, -9], up = [0, 1, 0], fov = 2 * atan(0.2), "
        "projection = \"orthographic\");\n"
        "light([1, 0.5, 4]);\n"
        "material(color = [1, 1, 1], ambient = 0, diffuse = 0.6, specular = 0.3, "
        "shininess = 20) halfspace([0, 0, 1], 0);\n"
        "material(color = [1, 1, 1], ambient = 0, diffuse = 1, specular = 0) "
        "translate([-1, -10, 1.5]) cube([1, 20, 0.5]);\n";
    const int n = 16;
    const Rendered r = render(load(source), n, n);
    const csg::Vec3 light(1.0, 0.5, 4.0), view(0.0, 0.0, 1.0);
    int shadowed = 0, lit = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            // The pixel's centre on the plane (the view is 4 x 4 units around the origin).
            const csg::Vec3 p(-2.0 + (i + 0.5) * 4.0 / n, 2.0 - (j + 0.5) * 4.0 / n, 0.0);
            // In the shadow when the segment to the light crosses the bar: its x at the
            // bar's bottom and top (z = 1.5, 2) overlaps [-1, 0]. Pixels within 1e-3 of the
            // shadow's edge would depend on rounding; the grid of centres has none.
            const auto xAt = [&](double z) { return p.x + (light.x - p.x) * z / light.z; };
            const double lo = std::min(xAt(1.5), xAt(2.0)), hi = std::max(xAt(1.5), xAt(2.0));
            ASSERT_TRUE(std::abs(lo) > 1e-3 && std::abs(hi + 1.0) > 1e-3) << i << "," << j;
            const bool inShadow = hi > -1.0 && lo < 0.0;
            double want = 0.0;
            if (!inShadow) {
                const csg::Vec3 l = glm::normalize(light - p);
                const csg::Vec3 h = glm::normalize(l + view);
                want = 0.6 * l.z + 0.3 * std::pow(h.z, 20.0);
            }
            (inShadow ? shadowed : lit)++;
            const csg::Vec3 got = pixel(r.result, i, j);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], want, 1e-6) << "pixel " << i << "," << j << " channel " << c;
        }
    }
    EXPECT_GE(shadowed, n);  // at least a column of the image lies in the shadow
    EXPECT_GE(lit, n * n / 2);
}

TEST(LightThroughGlass, PlanCountsOneShadowRayPerLitPointAndNoneWhereNothingOccludes) {
    // Every pixel sees the plane and casts exactly one shadow ray toward the one light, glass
    // or not in its way: filtering changes the light, not the rays.
    const int n = kShadowImage;
    for (const std::string& slab : {glassSlab(2, "[1, 1, 1]", 0.6),
                                    std::string("translate([-10, -10, 2]) cube([10, 20, 1]);")}) {
        const Rendered r = render(load(planeUnder(slab)), n, n);
        EXPECT_TRUE(r.plan.shadowRays);
        EXPECT_EQ(r.result.rays.primary, uint64_t(n * n));
        EXPECT_EQ(r.result.rays.shadow, uint64_t(n * n));
        EXPECT_EQ(r.result.rays.reflection, 0u);
        EXPECT_EQ(r.result.rays.refraction, 0u);
    }
    // One convex glass solid cannot occlude its own lit side: no shadow rays, as for any convex
    // scene, though it refracts.
    const LoadedScene glass = load(
        "light([3, -4, 5]); material(ambient = 0.1, diffuse = 0.5, transmit = 0.7) sphere(1);");
    const Rendered r = render(glass, 32, 32);
    EXPECT_TRUE(r.plan.convexScene);
    EXPECT_FALSE(r.plan.shadowRays);
    EXPECT_EQ(r.result.rays.shadow, 0u);
    EXPECT_GT(r.result.rays.refraction, 0u);
}

// ---- output ----

struct DecodedPng {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
    bool srgb = false;
};

DecodedPng decodePng(const fs::path& path) {
    DecodedPng out;
    FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) return out;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        std::fclose(file);
        return DecodedPng{};
    }
    png_init_io(png, file);
    png_read_info(png, info);
    int intent = 0;
    out.srgb = png_get_sRGB(png, info, &intent) != 0;
    out.width = int(png_get_image_width(png, info));
    out.height = int(png_get_image_height(png, info));
    if (png_get_color_type(png, info) != PNG_COLOR_TYPE_RGB || png_get_bit_depth(png, info) != 8)
        ADD_FAILURE() << "expected 8-bit RGB";
    out.rgb.resize(size_t(out.width) * out.height * 3);
    for (int y = 0; y < out.height; ++y)
        png_read_row(png, out.rgb.data() + size_t(y) * out.width * 3, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(file);
    return out;
}

using csg::testing::TempDir;

TEST(Output, PngIsSrgbEncodedAndDecodesBack) {
    // An ambient-only white square (ambient 0.5: linear 0.5) on a background of sRGB 0.4,
    // seen straight on by an orthographic camera.
    const LoadedScene s = load(R"(
        camera(eye=[0, 0, 10], center=[0, 0, 0], up=[0, 1, 0], fov=40, projection="orthographic");
        background([0.4, 0.4, 0.4]);
        material(color=[1, 1, 1], ambient=0.5, diffuse=0, specular=0) cube([1, 1, 1], center=true);
    )");
    const Rendered r = render(s, 48, 32);
    const TempDir temp("render_test_png");
    const fs::path& dir = temp.path;
    const fs::path png = dir / "out.png";
    ASSERT_EQ(writeImage(png, ImageFormat::Png, r.result.image), "");
    const DecodedPng image = decodePng(png);
    ASSERT_EQ(image.width, 48);
    ASSERT_EQ(image.height, 32);
    EXPECT_TRUE(image.srgb) << "the file says its pixels are sRGB";
    // The corner is the background: sRGB 0.4 in, 0.4 * 255 = 102 out (decode, encode).
    EXPECT_EQ(image.rgb[0], 102);
    // The centre is linear 0.5, which sRGB encodes as 188 (a plain linear write gives 128).
    const size_t centre = (size_t(16) * 48 + 24) * 3;
    EXPECT_EQ(image.rgb[centre], 188);
    EXPECT_EQ(image.rgb[centre + 1], 188);
    // PFM keeps the linear value.
    const fs::path pfm = dir / "out.pfm";
    ASSERT_EQ(writeImage(pfm, ImageFormat::Pfm, r.result.image), "");
    std::ifstream in(pfm, std::ios::binary);
    std::string magic, scale;
    int pw = 0, ph = 0;
    in >> magic >> pw >> ph >> scale;
    in.get();
    EXPECT_EQ(magic, "PF");
    EXPECT_EQ(pw, 48);
    EXPECT_EQ(ph, 32);
    std::vector<float> floats(size_t(pw) * ph * 3);
    in.read(reinterpret_cast<char*>(floats.data()), std::streamsize(floats.size() * 4));
    EXPECT_FLOAT_EQ(floats[(size_t(16) * 48 + 24) * 3], 0.5f);
}

TEST(Output, ExrHoldsTheLinearFloatsAndWritesAtomically) {
    // A shaded sphere: many distinct floats, read back with OpenEXR's own reader.
    const LoadedScene s = load(R"(
        camera(eye=[0, -6, 2], center=[0, 0, 0], up=[0, 0, 1], fov=40);
        light([4, -4, 6]);
        sphere(1);
    )");
    const Rendered r = render(s, 40, 30);
    const TempDir temp("render_test_exr");
    const fs::path& dir = temp.path;
    const fs::path exr = dir / "out.exr";
    ASSERT_EQ(writeImage(exr, ImageFormat::Exr, r.result.image), "");
    Imf::InputFile in(exr.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    ASSERT_EQ(window.max.x - window.min.x + 1, 40);
    ASSERT_EQ(window.max.y - window.min.y + 1, 30);
    std::vector<float> rgb(size_t(40) * 30 * 3, -1.0f);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c),
                                          3 * sizeof(float), 3 * sizeof(float) * 40));
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    EXPECT_EQ(rgb, r.result.image.rgb);  // FLOAT channels, lossless compression: bit for bit
    // An unwritable target is an error and leaves nothing behind.
    const fs::path missing = dir / "no-such-dir" / "out.exr";
    EXPECT_NE(writeImage(missing, ImageFormat::Exr, r.result.image), "");
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(Output, FastSrgbEncodingAgreesWithTheTransferFunction) {
    // Every float near each code boundary, a sweep of [0, 1], and out-of-range values.
    LinearImage image;
    std::vector<float>& v = image.rgb;
    for (int k = 0; k < 256; ++k) {
        float f = float(srgbToLinear((k + 0.5) / 255.0));
        for (int i = 0; i < 8; ++i) f = std::nextafter(f, 0.0f);
        for (int i = 0; i < 16; ++i, f = std::nextafter(f, 2.0f)) v.push_back(f);
    }
    for (int i = 0; i <= 300000; ++i) v.push_back(float(i) / 300000.0f);
    for (const float f : {-1.0f, 0.0f, 1.0f, 1.5f, 1e30f, 1e-40f}) v.push_back(f);
    // Both sides of every place where the top 16 bits of a positive float change (the
    // encoder's lookup buckets), up to 2.
    for (uint32_t top = 1; top <= (std::bit_cast<uint32_t>(2.0f) >> 16); ++top) {
        v.push_back(std::bit_cast<float>(top << 16));
        v.push_back(std::bit_cast<float>((top << 16) - 1));
    }
    while (v.size() % 3) v.push_back(0.5f);
    image.width = int(v.size() / 3);
    image.height = 1;
    const render::Rgb8Image encoded = encodeSrgb(image);
    for (size_t i = 0; i < v.size(); ++i)
        ASSERT_EQ(encoded.pixels[i], linearToSrgb8(v[i])) << "linear " << v[i];
}

TEST(Materials, PresetsMatchTheirClasses) {
    EXPECT_EQ(materialPreset(MaterialClass::BlackBody).ambient, 0.0);
    EXPECT_EQ(materialPreset(MaterialClass::BlackBody).diffuse, 0.0);
    EXPECT_EQ(materialPreset(MaterialClass::Ambient).ambient, 1.0);
    EXPECT_EQ(materialPreset(MaterialClass::Diffuse).diffuse, 0.9);
    EXPECT_EQ(materialPreset(MaterialClass::Specular).specular, 0.5);
    EXPECT_EQ(materialPreset(MaterialClass::Mirror).reflect, 0.9);
    EXPECT_EQ(materialPreset(MaterialClass::Transparent).transmit, 0.9);
    EXPECT_EQ(materialPreset(MaterialClass::Transparent).ior, 1.5);
}

TEST(Materials, HighlightIsThePowerWithinItsErrorBound) {
    // Against long double's pow (11 more bits): squaring stays within shininess * 2^-53
    // relative, plus an absolute hair where the power underflows to subnormals.
    csg::testing::Rng rng(4);
    for (const double shininess : {1.0, 2.0, 3.0, 7.0, 50.0, 64.0, 200.0, 999.0, 1024.0}) {
        const ShadingMaterial s = shadingMaterial(render::Material{.shininess = shininess});
        ASSERT_EQ(s.wholeShininess, uint32_t(shininess));
        for (int i = 0; i < 20000; ++i) {
            const double cos = i == 0 ? 1.0 : i == 1 ? 0.0 : 1.0 - std::pow(rng.uniform(), 3.0);
            const long double exact = std::pow((long double)cos, (long double)shininess);
            const double bound = double(exact) * shininess * 0x1p-53 + 1e-300;
            ASSERT_NEAR(highlight(cos, s), double(exact), bound) << cos << "^" << shininess;
        }
    }
    // Other exponents are std::pow's.
    for (const double shininess : {0.5, 12.25, 1025.0, 0.0}) {
        const ShadingMaterial s = shadingMaterial(render::Material{.shininess = shininess});
        EXPECT_EQ(s.wholeShininess, 0u);
        EXPECT_EQ(highlight(0.73, s), std::pow(0.73, shininess));
    }
}

TEST(Sampling, StratifiedSamplesStayInTheirStrataAndRepeat) {
    for (int n : {1, 2, 4}) {
        for (int sy = 0; sy < n; ++sy) {
            for (int sx = 0; sx < n; ++sx) {
                double u, v, u2, v2;
                samplePosition(7, 9, sx, sy, n, u, v);
                samplePosition(7, 9, sx, sy, n, u2, v2);
                EXPECT_EQ(u, u2);
                EXPECT_EQ(v, v2);
                EXPECT_GE(u, double(sx) / n);
                EXPECT_LT(u, double(sx + 1) / n);
                EXPECT_GE(v, double(sy) / n);
                EXPECT_LT(v, double(sy + 1) / n);
            }
        }
    }
}

TEST(Threads, ImageDoesNotDependOnTheThreadCount) {
    const LoadedScene s = load(scaledScene(1.0));
    const Rendered one = render(s, 40, 30, {}, 1);
    const Rendered three = render(s, 40, 30, {}, 3);
    EXPECT_EQ(one.result.image.rgb, three.result.image.rgb);
    EXPECT_EQ(one.result.rays.total(), three.result.rays.total());
}

// A PNG render keeps only each tile's 8-bit encoding: the same bytes as encoding the float
// image, on sizes that cut tiles (16 pixels) at the right and bottom, with anti-aliasing.
TEST(Threads, TilesEncodedToSrgbAreTheFloatImageEncoded) {
    const LoadedScene s = load(scaledScene(1.0));
    for (const auto& [width, height] : {std::pair{40, 30}, {17, 33}, {1, 1}}) {
        const Rendered linear = render(s, width, height, {}, 2, PixelStore::LinearFloat, 2);
        const Rendered srgb = render(s, width, height, {}, 3, PixelStore::Srgb8, 2);
        EXPECT_TRUE(srgb.result.image.rgb.empty());
        const render::Rgb8Image want = encodeSrgb(linear.result.image);
        ASSERT_EQ(srgb.result.srgb.width, width);
        ASSERT_EQ(srgb.result.srgb.height, height);
        EXPECT_EQ(srgb.result.srgb.pixels, want.pixels) << width << "x" << height;
    }
}

// Every pixel's primary ray of the scene's camera, traced twice by one Tracer: the heap
// allocations of the second frame (the first is the warm-up, where the context's scratch grows
// to its largest ray), the tracer's ray counts and the colour sum over both frames.
struct WarmFrame {
    long allocations;
    RayCounts rays;
    csg::Vec3 sum;
};
WarmFrame traceTwice(const LoadedScene& s, int width, int height) {
    const render::Camera camera = *s.model.camera;
    const EffectsPlan plan = makeEffectsPlan(s.model, s.model.root.get(), s.scene, camera, {});
    const RenderCamera view(camera, width, height);
    Tracer tracer(s.scene, plan);
    csg::Vec3 sum(0.0);
    auto frame = [&] {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) sum += tracer.tracePrimary(view.ray(x + 0.5, y + 0.5));
    };
    frame();
    const long before = csg::testing::allocations.load();
    frame();
    return {csg::testing::allocations.load() - before, tracer.rays, sum};
}

TEST(Tracer, AllocatesNothingPerRayOnceWarm) {
    // Every effect at once: shadows, reflection, refraction through a cut glass part.
    const WarmFrame f = traceTwice(load(scaledScene(1.0)), 64, 48);
    EXPECT_EQ(f.allocations, 0);
    EXPECT_GT(f.rays.shadow + f.rays.reflection + f.rays.refraction, 0u);
    EXPECT_GT(f.sum.r, 0.0);
}

// ---- patterns (material(pattern="checker") and material(texture="file.png")) ----

// Looking straight down at z = 0 with an orthographic camera: eye 10 above, up = +y, so
// forward = -z and right = forward x up = +x. fov = 2 atan(0.2) makes the view 2 * 10 * 0.2 =
// 4 units tall, so a square image of N pixels shows [-2, 2] x [-2, 2] and pixel (i, j) has its
// centre at x = -2 + (i + 0.5) 4/N, y = 2 - (j + 0.5) 4/N. Ambient-only materials make a pixel
// exactly the linear colour of the pattern there.
std::string topDownScene(const std::string& material) {
    return "camera(eye = [0, 0, 10], center = [0, 0, 0], up = [0, 1, 0], fov = 2 * atan(0.2), "
           "projection = \"orthographic\");\n" +
           material + " halfspace([0, 0, 1], 0);\n";
}

TEST(Patterns, CheckerHalfSpaceSeenFromAboveAlternatesByTheSquare) {
    // Red and blue squares of side 1: blue where floor(x) + floor(y) is odd.
    const LoadedScene s = load(topDownScene(
        "material(color = [1, 0, 0], color2 = [0, 0, 1], pattern = \"checker\", scale = 1, "
        "ambient = 1, diffuse = 0, specular = 0)"));
    const Rendered r = render(s, 8, 8);
    const csg::Vec3 red(1, 0, 0), blue(0, 0, 1);
    // 8 pixels over 4 units: centres at +-0.25, +-0.75, ... (x to the right, y up).
    struct Expected {
        int i, j;
        csg::Vec3 color;
        const char* why;
    };
    const Expected expected[] = {
        {0, 0, blue, "(-1.75, 1.75): floor -2 + 1 = -1, odd"},
        {1, 0, blue, "(-1.25, 1.75): same square"},
        {2, 0, red, "(-0.75, 1.75): -1 + 1 = 0, even"},
        {4, 0, blue, "(0.25, 1.75): 0 + 1 = 1, odd"},
        {0, 2, red, "(-1.75, 0.75): -2 + 0, even"},
        {3, 3, blue, "(-0.25, 0.25): -1 + 0, odd"},
        {4, 4, blue, "(0.25, -0.25): 0 - 1, odd"},
        {4, 3, red, "(0.25, 0.25): 0 + 0, even"},
        {7, 7, blue, "(1.75, -1.75): 1 - 2 = -1, odd"},
    };
    for (const Expected& e : expected)
        EXPECT_EQ(pixel(r.result, e.i, e.j), e.color)
            << "pixel " << e.i << "," << e.j << " at " << e.why;
    // Every pixel is one of the two colours, and each row alternates every two pixels.
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i + 2 < 8; i += 2)
            EXPECT_NE(pixel(r.result, i, j), pixel(r.result, i + 2, j)) << i << "," << j;
}

TEST(Patterns, CheckerOnATiltedHalfSpaceUsesThePlanesOwnFrame) {
    // The plane frame is orthonormal: moving one square along either in-plane axis flips the
    // colour, and its frame is x, y itself on an axis-aligned plane.
    const csg::Vec3 n = glm::normalize(csg::Vec3(0.3, -0.2, 1.0));
    const csg::Vec2 origin = planarCoordinates(csg::Vec3(0.0), n, true);
    EXPECT_EQ(origin, csg::Vec2(0.0));
    const csg::Vec2 flat = planarCoordinates(csg::Vec3(1.5, -2.5, 7.0), csg::Vec3(0, 0, 1), true);
    EXPECT_EQ(flat, csg::Vec2(1.5, -2.5));
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> coord(-50.0, 50.0);
    for (int k = 0; k < 1000; ++k) {
        // Two points of the plane a distance d apart map to (u, v) a distance d apart.
        csg::Vec3 a(coord(rng), coord(rng), coord(rng)), b(coord(rng), coord(rng), coord(rng));
        a -= glm::dot(a, n) * n;
        b -= glm::dot(b, n) * n;
        const double d = glm::length(planarCoordinates(a, n, true) - planarCoordinates(b, n, true));
        EXPECT_NEAR(d, glm::length(a - b), 1e-9 * (1.0 + glm::length(a - b)));
    }
}

// Colours equal to 1e-9 (componentwise distance), printing the actual one.
#define EXPECT_NEAR_RGB(actual, expected)                                 \
    EXPECT_LT(glm::length(csg::Vec3(actual) - csg::Vec3(expected)), 1e-9) \
        << #actual << " = " << (actual).x << "," << (actual).y << "," << (actual).z

TEST(Patterns, PngTextureIsSampledAtKnownPoints) {
    // A 2 x 2 texture over squares of side 2: red top-left, green top-right, blue bottom-left,
    // white bottom-right. Texel centres are at u, v = 0.5 and 1.5 of each tile, v up, so the
    // top row (red, green) is at v = 1.5.
    TempDir dir("render_texture");
    render::Rgb8Image image(2, 2);
    const uint8_t texels[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    std::copy(std::begin(texels), std::end(texels), image.pixels.begin());
    ASSERT_EQ(render::writePng(dir.path / "tex.png", image), "");
    // Read relative to the part file, not the working directory.
    const std::string source = topDownScene(
        "material(texture = \"tex.png\", scale = 2, ambient = 1, diffuse = 0, specular = 0)");
    io::EvaluateResult evaluated = io::evaluateString(source, (dir.path / "part.scad").string());
    ASSERT_TRUE(evaluated.ok()) << (evaluated.diagnostics.empty()
                                        ? std::string()
                                        : evaluated.diagnostics[0].message);
    LoadedScene s;
    s.model = std::move(*evaluated.model);
    s.scene = csg::Scene::compile(s.model.root);
    ASSERT_EQ(s.model.textures.size(), 1u);
    EXPECT_EQ(s.model.materials.back().pattern, render::Pattern::Texture);

    // 4 pixels over 4 units: centres at x, y = -1.5, -0.5, 0.5, 1.5, on texel centres.
    const Rendered r = render(s, 4, 4);
    const csg::Vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
    // Near, not equal: the camera's ray lands on a texel centre only to rounding, and the
    // bilinear weights pass that on (~1e-15).
    EXPECT_NEAR_RGB(pixel(r.result, 2, 0), red);    // (0.5, 1.5): tile (0, 0), top-left
    EXPECT_NEAR_RGB(pixel(r.result, 3, 0), green);  // (1.5, 1.5): top-right
    EXPECT_NEAR_RGB(pixel(r.result, 2, 1), blue);   // (0.5, 0.5): bottom-left
    EXPECT_NEAR_RGB(pixel(r.result, 3, 1), white);  // (1.5, 0.5): bottom-right
    EXPECT_NEAR_RGB(pixel(r.result, 0, 0), red);    // (-1.5, 1.5): the tile to the left, tiled
    EXPECT_NEAR_RGB(pixel(r.result, 1, 3), white);  // (-0.5, -1.5): the tile below-left
    // Half-way between texel centres the sample blends them (bilinear): red and green.
    const csg::Vec3 mid = sampleTexture(r.plan.textures[0], csg::Vec2(1.0, 1.5), 0.5);
    EXPECT_NEAR(mid.r, 0.5, 1e-12);
    EXPECT_NEAR(mid.g, 0.5, 1e-12);
    EXPECT_NEAR(mid.b, 0.0, 1e-12);
}

TEST(Patterns, MissingOrUnreadableTextureIsAnErrorAtItsArgument) {
    TempDir dir("render_texture_missing");
    std::ofstream(dir.path / "not_a.png") << "plain text";
    for (const char* name : {"missing.png", "not_a.png"}) {
        const std::string source = std::string("halfspace();\nmaterial(ambient = 1,\n") +
                                   "    texture = \"" + name + "\") sphere(1);\n";
        const io::EvaluateResult r = io::evaluateString(source, (dir.path / "part.scad").string());
        ASSERT_FALSE(r.ok()) << name;
        ASSERT_FALSE(r.diagnostics.empty());
        const io::Diagnostic& d = r.diagnostics.front();
        EXPECT_EQ(d.line, 3u) << d.message;
        EXPECT_EQ(d.col, 5u) << d.message;
        EXPECT_NE(d.message.find(name), std::string::npos) << d.message;
        EXPECT_NE(d.message.find("texture"), std::string::npos) << d.message;
    }
    // pattern="texture" without an image, and a bad scale, are errors with the expected form.
    for (const char* bad : {"material(pattern = \"texture\") sphere(1);",
                            "material(pattern = \"checker\", scale = 0) sphere(1);",
                            "material(pattern = \"stripes\") sphere(1);"}) {
        const io::EvaluateResult r = io::evaluateString(bad, "bad.scad");
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.diagnostics.front().message.find("expected"), std::string::npos)
            << r.diagnostics.front().message;
    }
}

TEST(Patterns, CheckerAllocatesNothingPerRay) {
    const LoadedScene s = load(
        "camera(eye = [3, -6, 4], center = [0, 0, 0]);\nlight([5, -5, 8]);\n"
        "material(pattern = \"checker\", color2 = \"black\") halfspace([0, 0, 1], -1);\n"
        "material(reflect = 0.5) sphere(1);\n");
    const WarmFrame f = traceTwice(s, 32, 32);
    EXPECT_EQ(f.allocations, 0);
    EXPECT_GT(f.sum.r, 0.0);
}

// ---- the command line ----

TEST(RenderCommand, StatsFileHasRaysQueriesPhasesAndThePlan) {
    const TempDir temp("render_stats");
    const fs::path& dir = temp.path;
    std::ofstream(dir / "mirrors.scad") << facingMirrors(0.5);
    const std::string command =
        std::string(CSGRAY_EXE) + " render '" + (dir / "mirrors.scad").string() + "' -o '" +
        (dir / "out.png").string() + "' --size 20x10 --quiet --stats '" +
        (dir / "stats.json").string() + "' 2>'" + (dir / "stderr").string() + "'";
    const auto launched = std::chrono::steady_clock::now();
    ASSERT_EQ(std::system(command.c_str()), 0);
    const double wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - launched).count();
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir / "stats.json"));
    EXPECT_EQ(stats["rays"]["primary"], 200);
    EXPECT_EQ(stats["rays"]["reflection"], 8 * 200);
    EXPECT_EQ(stats["rays"]["shadow"], 0);
    EXPECT_EQ(stats["rays"]["refraction"], 0);
    EXPECT_EQ(stats["queries"]["rays"], 9 * 200);
    EXPECT_GT(stats["queries"]["nodeVisits"].get<uint64_t>(), 0u);
    // The phases are consecutive parts of one process's run: none is negative, they add up
    // to the total, and the total fits in the wall time the test saw from outside (a phase
    // summed over threads, or in the wrong unit, would not). Reading the part, tracing 1,800
    // rays and writing the PNG each take measurable time.
    double phaseSum = 0.0;
    for (const char* phase : {"loadAndCompile", "plan", "render", "write"}) {
        const double seconds = stats["seconds"][phase].get<double>();
        EXPECT_GE(seconds, 0.0) << phase;
        phaseSum += seconds;
    }
    const double total = stats["seconds"]["total"].get<double>();
    EXPECT_NEAR(total, phaseSum, 1e-9);
    EXPECT_LE(total, wallSeconds);
    for (const char* phase : {"loadAndCompile", "render", "write"})
        EXPECT_GT(stats["seconds"][phase].get<double>(), 0.0) << phase;
    EXPECT_EQ(stats["plan"]["reflection"], true);
    EXPECT_EQ(stats["plan"]["refraction"], false);
    EXPECT_EQ(stats["plan"]["materials"][1]["reflection"], true);
    std::ifstream err(dir / "stderr");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(err), {}), "") << "--quiet";
}

// ---- Ctrl-C ----

TEST(Interrupt, CtrlCStopsTheRenderAndLeavesNoFile) {
    const TempDir temp("render_int");
    const fs::path& dir = temp.path;
    { std::ofstream(dir / "mirrors.scad") << facingMirrors(0.9); }
    // Far too much work to finish in the second before the interrupt (~10^9 rays).
    const std::string exe = CSGRAY_EXE, part = (dir / "mirrors.scad").string(),
                      out = (dir / "out.png").string();
    std::vector<std::string> args = {exe,         "render", part, "-o",      out,         "--size",
                                     "4000x4000", "--aa",   "4",  "--quiet", "--threads", "1"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    const auto sent = std::chrono::steady_clock::now();
    ASSERT_EQ(kill(pid, SIGINT), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    const double stopSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal, not stopped cleanly";
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_LT(stopSeconds, 5.0) << "workers stop between tiles";
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"mirrors.scad"}) << "no image, no temporary file";
}

}  // namespace
}  // namespace viewer::render
