#include "bench/BenchScenes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <random>
#include <stdexcept>

#include "primitives/Polyhedron.h"

namespace csg::bench {
namespace {

constexpr int kImageSize = 128;  // rays per benchmark iteration = kImageSize^2

constexpr double kLayerSide = 100.0;
// Fraction of the layer's area the spheres' discs would cover if they did not overlap.
constexpr double kLayerDiscCoverage = 0.5;

Mat4 translation(const Vec3& offset) {
    return glm::translate(Mat4(1.0), offset);
}

Mat4 rotation(double degrees, const Vec3& axis) {
    return glm::rotate(Mat4(1.0), glm::radians(degrees), axis);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::unique_ptr<BenchScene> makeScene(const std::string& key) {
    NodePtr tree;
    PinholeCamera camera;
    if (key == "sphere") {
        tree = singleSphereTree();
        camera = singleSphereCamera();
    } else if (key == "emblem_grid") {
        tree = emblemGridTree();
        camera = emblemGridCamera();
    } else if (key.starts_with("sphere_layer/")) {
        tree = sphereLayerTree(std::stoul(key.substr(key.find('/') + 1)));
        camera = sphereLayerCamera();
    } else if (key.starts_with("sphere_layer_narrow/")) {
        tree = sphereLayerTree(std::stoul(key.substr(key.find('/') + 1)));
        camera = sphereLayerNarrowCamera();
    } else {
        throw std::invalid_argument("no benchmark scene named " + key);
    }
    auto result = std::make_unique<BenchScene>();

    const auto compileStart = std::chrono::steady_clock::now();
    result->scene = Scene::compile(tree);
    result->compileSeconds = secondsSince(compileStart);
    result->leafCount = result->scene.leafCount();
    result->rays = camera.pixelRays(kImageSize, kImageSize);
    return result;
}

}  // namespace

std::vector<Ray> PinholeCamera::pixelRays(int width, int height) const {
    const Vec3 forward = glm::normalize(lookAt - eye);
    const Vec3 right = glm::normalize(glm::cross(forward, up));
    const Vec3 trueUp = glm::cross(right, forward);
    const double halfWidth = std::tan(glm::radians(horizontalFovDegrees) / 2.0);
    const double halfHeight = halfWidth * height / width;
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(width) * height);
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column) {
            const double u = (2.0 * (column + 0.5) / width - 1.0) * halfWidth;
            const double v = (1.0 - 2.0 * (row + 0.5) / height) * halfHeight;
            rays.push_back({eye, glm::normalize(forward + u * right + v * trueUp)});
        }
    }
    return rays;
}

const BenchScene& cachedScene(const std::string& key) {
    // Benchmarks run one at a time, but a mutex keeps the cache right under ->Threads(n) too.
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<BenchScene>> cache;
    const std::lock_guard lock(mutex);
    std::unique_ptr<BenchScene>& slot = cache[key];
    if (!slot) slot = makeScene(key);
    return *slot;
}

NodePtr singleSphereTree() {
    return leaf(Sphere{1.0});
}

PinholeCamera singleSphereCamera() {
    PinholeCamera camera;
    camera.eye = {0.0, 0.0, -4.0};
    camera.lookAt = {0.0, 0.0, 0.0};
    // The silhouette of a unit sphere seen from distance 4 subtends asin(1/4) each side.
    camera.horizontalFovDegrees = 2.0 * glm::degrees(std::asin(0.25));
    return camera;
}

NodePtr emblemGridTree() {
    // One part, shared by all 1000 instances (only the transform differs).
    const NodePtr cube = leaf(Box{Vec3(-0.5), Vec3(0.5)});
    const NodePtr ball = leaf(Sphere{0.68});
    // Cylinder runs along +z from z = 0; centre it, then turn it onto each axis.
    const NodePtr rodZ = transformed(translation({0, 0, -1}), leaf(Cylinder{2.0, 0.3, 0.3}));
    const NodePtr rodX = transformed(rotation(90.0, {0, 1, 0}), rodZ);
    const NodePtr rodY = transformed(rotation(-90.0, {1, 0, 0}), rodZ);
    const NodePtr part = subtractAll(intersect(cube, ball), {rodX, rodY, rodZ});

    std::vector<NodePtr> parts;
    parts.reserve(1000);
    for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 10; ++j) {
            for (int k = 0; k < 10; ++k) {
                // POV's rotate <a, b, c> turns about x by a, then y by b, then z by c.
                const Mat4 placement = translation({i, j, k}) * rotation(7.0 * k, {0, 0, 1}) *
                                       rotation(17.0 * j, {0, 1, 0}) *
                                       rotation(13.0 * i, {1, 0, 0});
                parts.push_back(transformed(placement, part));
            }
        }
    }
    return uniteAll(parts);
}

PinholeCamera emblemGridCamera() {
    PinholeCamera camera;
    camera.eye = {14.0, 12.0, -22.0};
    camera.lookAt = {4.5, 4.5, 4.5};
    camera.horizontalFovDegrees = 40.0;
    return camera;
}

NodePtr sphereLayerTree(size_t sphereCount) {
    const double radius =
        kLayerSide * std::sqrt(kLayerDiscCoverage / (std::numbers::pi * sphereCount));
    const NodePtr ball = leaf(Sphere{radius});
    // Own uniform mapping from raw 64-bit draws: std::uniform_real_distribution is not
    // specified bit for bit, and the scene should be the same with any standard library.
    std::mt19937_64 random(20240601);
    auto uniform = [&random] { return static_cast<double>(random() >> 11) * 0x1.0p-53; };
    std::vector<NodePtr> spheres;
    spheres.reserve(sphereCount);
    for (size_t i = 0; i < sphereCount; ++i) {
        const Vec3 centre(kLayerSide * uniform(), kLayerSide * uniform(), 2.0 * radius * uniform());
        spheres.push_back(transformed(translation(centre), ball));
    }
    return uniteAll(spheres);
}

NodePtr terrainMeshTree(size_t triangleCount) {
    const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(triangleCount / 2.0))));
    const double step = kLayerSide / side;
    std::vector<Vec3> points;
    PolygonFaces faces;
    const auto top = [&](int i, int j) { return static_cast<uint32_t>(j * (side + 1) + i); };
    for (int j = 0; j <= side; ++j)
        for (int i = 0; i <= side; ++i) {
            const double x = step * i, y = step * j;
            points.emplace_back(x, y,
                                2.0 + 1.5 * std::sin(0.23 * x) * std::cos(0.31 * y) +
                                    0.8 * std::sin(0.9 * x + 0.6 * y));
        }
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            faces.add({top(i, j), top(i + 1, j), top(i + 1, j + 1)});
            faces.add({top(i, j), top(i + 1, j + 1), top(i, j + 1)});
        }
    // The rim counter-clockwise from above, a wall quad down from each of its edges, the floor.
    std::vector<uint32_t> rim;
    for (int i = 0; i < side; ++i) rim.push_back(top(i, 0));
    for (int j = 0; j < side; ++j) rim.push_back(top(side, j));
    for (int i = side; i > 0; --i) rim.push_back(top(i, side));
    for (int j = side; j > 0; --j) rim.push_back(top(0, j));
    const uint32_t floorStart = static_cast<uint32_t>(points.size());
    for (const uint32_t r : rim) points.emplace_back(points[r].x, points[r].y, -1.0);
    const uint32_t n = static_cast<uint32_t>(rim.size());
    for (uint32_t k = 0; k < n; ++k)
        faces.add({rim[k], floorStart + k, floorStart + (k + 1) % n, rim[(k + 1) % n]});
    for (uint32_t k = n; k-- > 0;) faces.corners.push_back(floorStart + k);
    faces.closeFace();
    return leaf(Polyhedron::make(std::move(points), faces));
}

NodePtr clusteredLayerTree(size_t sphereCount) {
    const double radius =
        kLayerSide * std::sqrt(kLayerDiscCoverage / (std::numbers::pi * sphereCount));
    const NodePtr ball = leaf(Sphere{radius});
    std::mt19937_64 random(20240602);
    auto uniform = [&random] { return static_cast<double>(random() >> 11) * 0x1.0p-53; };
    constexpr int kClusters = 16;
    constexpr double kClusterRadius = 4.0;
    Vec3 centres[kClusters];
    for (Vec3& c : centres) {
        const double x = kLayerSide * (0.1 + 0.8 * uniform());
        const double y = kLayerSide * (0.1 + 0.8 * uniform());
        c = {x, y, 0.0};
    }
    std::vector<NodePtr> spheres;
    spheres.reserve(sphereCount);
    for (size_t i = 0; i < sphereCount; ++i) {
        // A point of the unit ball by rejection, drawn in order (x, then y, then z).
        Vec3 p;
        do {
            const double x = 2.0 * uniform() - 1.0;
            const double y = 2.0 * uniform() - 1.0;
            const double z = 2.0 * uniform() - 1.0;
            p = {x, y, z};
        } while (glm::dot(p, p) > 1.0);
        const Vec3 centre = centres[i % kClusters] + kClusterRadius * p;
        spheres.push_back(transformed(translation(centre), ball));
    }
    return uniteAll(spheres);
}

PinholeCamera sphereLayerCamera() {
    // Above and in front of the layer, looking down at its centre at about 40 degrees from the
    // vertical; the far corners and the sky above the far edge are misses.
    PinholeCamera camera;
    camera.eye = {0.5 * kLayerSide, -0.4 * kLayerSide, 1.1 * kLayerSide};
    camera.lookAt = {0.5 * kLayerSide, 0.5 * kLayerSide, 0.0};
    camera.up = {0.0, 0.0, 1.0};
    camera.horizontalFovDegrees = 40.0;
    return camera;
}

PinholeCamera sphereLayerNarrowCamera() {
    PinholeCamera camera = sphereLayerCamera();
    camera.horizontalFovDegrees = 0.4;
    return camera;
}

}  // namespace csg::bench
