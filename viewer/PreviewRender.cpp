#include "viewer/PreviewRender.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

namespace viewer {

namespace {

double degrees(double radians) {
    return radians * 180.0 / std::numbers::pi;
}
double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

// Material colors are sRGB values as written in the part; lighting is done in linear light.
double toLinear(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
uint8_t toSrgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double c =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return uint8_t(std::lround(c * 255.0));
}

// The primary ray through pixel centres of an image, for either projection.
struct PixelRays {
    csg::Vec3 eye, forward, right, up;
    double halfHeight;  // tan(fov/2) for perspective; world half-height for orthographic
    double aspect;
    bool orthographic;
    int width, height;

    PixelRays(const io::Camera& c, int w, int h)
        : eye(c.eye), aspect(double(w) / double(h)), width(w), height(h) {
        forward = glm::normalize(c.center - c.eye);
        right = glm::cross(forward, c.up);
        // An up vector along the view direction leaves no roll defined: pick any.
        if (glm::length(right) < 1e-12) right = glm::cross(forward, csg::Vec3(1.0, 0.0, 0.0));
        if (glm::length(right) < 1e-12) right = glm::cross(forward, csg::Vec3(0.0, 1.0, 0.0));
        right = glm::normalize(right);
        up = glm::cross(right, forward);
        orthographic = c.projection == io::Projection::Orthographic;
        const double tanHalf = std::tan(radians(std::clamp(c.fov, 1e-3, 179.0)) / 2.0);
        halfHeight = orthographic ? tanHalf * glm::length(c.center - c.eye) : tanHalf;
    }

    csg::Ray at(int x, int y) const {
        const double sx = (2.0 * (x + 0.5) / width - 1.0) * halfHeight * aspect;
        const double sy = (1.0 - 2.0 * (y + 0.5) / height) * halfHeight;
        if (orthographic) return csg::Ray{eye + sx * right + sy * up, forward, 0.0, csg::kInfinity};
        return csg::Ray{eye, glm::normalize(forward + sx * right + sy * up), 0.0, csg::kInfinity};
    }
};

}  // namespace

io::Camera frameBounds(const csg::Scene& scene, double aspect) {
    csg::Bounds3 box;
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf) {
        const csg::Bounds3 local =
            std::visit([](const auto& p) { return p.bounds(); }, scene.leafPrimitive(leaf));
        const csg::Bounds3 world = csg::transformBounds(scene.leafWorldFromLocal(leaf), local);
        if (world.finite()) box.extend(world);
    }
    // A difference or intersection can make the part smaller than its leaves, never larger;
    // the scene's bounds already apply that, so take the overlap when it is finite.
    const csg::Bounds3 sceneBox = scene.bounds();
    if (sceneBox.finite() && !sceneBox.empty()) box = overlap(box, sceneBox);
    io::Camera camera;
    if (box.empty()) return camera;

    const double radius = std::max(0.5 * glm::length(box.extent()), 1e-9);
    const double fovV = camera.fov;
    const double fovH = 2.0 * degrees(std::atan(std::tan(radians(fovV) / 2.0) * aspect));
    const double fov = std::min(fovV, fovH);
    // The bounding sphere fits the narrower field of view with a 5% margin.
    const double distance = 1.05 * radius / std::sin(radians(fov) / 2.0);
    const csg::Vec3 viewFrom = glm::normalize(csg::Vec3(1.0, -1.6, 1.1));
    camera.center = box.center();
    camera.eye = camera.center + distance * viewFrom;
    camera.up = csg::Vec3(0.0, 0.0, 1.0);
    return camera;
}

io::Rgb8Image renderPreview(const io::Model& model, const csg::Scene& scene, int width, int height,
                            int threads) {
    io::Rgb8Image image(width, height);
    const double aspect = double(width) / double(height);
    const io::Camera camera = model.camera ? *model.camera : frameBounds(scene, aspect);
    const PixelRays rays(camera, width, height);
    const csg::Vec3 background = model.background ? *model.background : kDefaultBackground;
    uint8_t backgroundPixel[3];
    for (int i = 0; i < 3; ++i) backgroundPixel[i] = toSrgb8(toLinear(background[i]));

    // Linear colors per material, looked up by the leaf's tag.
    std::vector<csg::Vec3> linearColors;
    for (const io::Material& m : model.materials)
        linearColors.emplace_back(toLinear(m.color.r), toLinear(m.color.g), toLinear(m.color.b));

    std::atomic<int> nextRow{0};
    auto work = [&]() {
        csg::QueryContext ctx;
        for (int y; (y = nextRow.fetch_add(1)) < height;) {
            uint8_t* row = image.row(y);
            for (int x = 0; x < width; ++x) {
                uint8_t* px = row + 3 * x;
                const csg::Ray ray = rays.at(x, y);
                const std::optional<csg::Hit> hit = scene.closest(ray, ctx);
                if (!hit || !hit->isSurface()) {
                    std::copy(backgroundPixel, backgroundPixel + 3, px);
                    continue;
                }
                const csg::SurfacePoint sp = scene.surface(ray, *hit);
                const uint32_t material = scene.leafTags(hit->leaf).material;
                const csg::Vec3& color =
                    linearColors[material < linearColors.size() ? material : 0];
                // Headlight: the light sits at the eye, so the cosine is with the view ray.
                // abs() lights a back face seen from inside the solid rather than blacking it.
                const double lambert = std::abs(glm::dot(sp.normal, ray.d));
                const double shade = 0.15 + 0.85 * lambert;
                for (int i = 0; i < 3; ++i) px[i] = toSrgb8(color[i] * shade);
            }
        }
    };
    std::vector<std::jthread> helpers;
    for (int t = 1; t < threads; ++t) helpers.emplace_back(work);
    work();
    helpers.clear();  // joins: every row is written before the image is handed back
    return image;
}

}  // namespace viewer
