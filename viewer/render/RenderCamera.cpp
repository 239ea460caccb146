#include "viewer/render/RenderCamera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

namespace viewer::render {

namespace {

double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

// A unit vector perpendicular to forward, as close to the requested up as possible. An up
// along the view direction leaves the roll undefined: then any perpendicular will do.
csg::Vec3 rightOf(const csg::Vec3& forward, const csg::Vec3& up) {
    // Only an exactly parallel (or zero) up is rejected: a nearly parallel one still gives a
    // well-defined, if arbitrary-looking, roll after normalization.
    csg::Vec3 right = glm::cross(forward, up);
    if (glm::length(right) == 0.0) right = glm::cross(forward, csg::Vec3(1, 0, 0));
    if (glm::length(right) == 0.0) right = glm::cross(forward, csg::Vec3(0, 1, 0));
    return glm::normalize(right);
}

}  // namespace

Camera frameBounds(const csg::Scene& scene, double aspect) {
    csg::Bounds3 box;
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf) {
        const csg::Bounds3 local =
            std::visit([](const auto& p) { return p.bounds(); }, scene.leafPrimitive(leaf));
        const csg::Bounds3 world = csg::transformBounds(scene.leafWorldFromLocal(leaf), local);
        if (world.finite()) box.extend(world);
    }
    // A difference or intersection makes the part smaller than its leaves, never larger.
    const csg::Bounds3 sceneBox = scene.bounds();
    if (!box.empty() && !sceneBox.empty()) {
        const csg::Bounds3 clipped = overlap(box, sceneBox);
        if (!clipped.empty()) box = clipped;
    }
    Camera camera;
    if (box.empty()) return camera;

    const double radius = std::max(0.5 * glm::length(box.extent()), 1e-300);
    const double halfV = radians(camera.fov) / 2.0;
    const double halfH = std::atan(std::tan(halfV) * aspect);
    const double distance = 1.05 * radius / std::sin(std::min(halfV, halfH));
    const csg::Vec3 viewFrom = glm::normalize(csg::Vec3(1.0, -1.6, 1.1));
    camera.center = box.center();
    camera.eye = camera.center + distance * viewFrom;
    camera.up = csg::Vec3(0.0, 0.0, 1.0);
    return camera;
}

RenderCamera::RenderCamera(const Camera& c, int width, int height)
    : eye_(c.eye),
      aspect_(double(width) / double(height)),
      orthographic_(c.projection == Projection::Orthographic),
      width_(width),
      height_(height) {
    const csg::Vec3 view = c.center - c.eye;
    focusDistance_ = glm::length(view);
    forward_ = view / focusDistance_;
    right_ = rightOf(forward_, c.up);
    up_ = glm::cross(right_, forward_);
    const double tanHalf = std::tan(radians(std::clamp(c.fov, 1e-3, 179.0)) / 2.0);
    halfHeight_ = orthographic_ ? tanHalf * focusDistance_ : tanHalf;
}

}  // namespace viewer::render
