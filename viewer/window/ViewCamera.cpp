#include "viewer/window/ViewCamera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "viewer/render/RenderCamera.h"

namespace viewer::window {

namespace {

// Rodrigues' rotation of v about the unit axis by angle radians.
csg::Vec3 rotate(const csg::Vec3& v, const csg::Vec3& axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

// World units per pixel at the centre's distance: what makes a pan follow the mouse.
double worldPerPixel(const render::Camera& camera, int height) {
    const double distance = glm::length(camera.center - camera.eye);
    const double halfHeight = std::tan(camera.fov * std::numbers::pi / 360.0) * distance;
    return 2.0 * halfHeight / std::max(height, 1);
}

}  // namespace

void ViewCamera::orbit(double dx, double dy, int height) {
    // A drag across the window's height turns the part by about 180 degrees.
    const double radiansPerPixel = std::numbers::pi / std::max(height, 1);
    const csg::Vec3 up = glm::normalize(camera_.up);
    csg::Vec3 offset = camera_.eye - camera_.center;
    offset = rotate(offset, up, -dx * radiansPerPixel);
    // Pitch, clamped 1 degree short of the poles, where the roll would become undefined.
    const double distance = glm::length(offset);
    const double elevation = std::asin(std::clamp(glm::dot(offset, up) / distance, -1.0, 1.0));
    const double limit = std::numbers::pi / 2.0 - std::numbers::pi / 180.0;
    const double target = std::clamp(elevation + dy * radiansPerPixel, -limit, limit);
    const csg::Vec3 right = glm::normalize(glm::cross(up, offset));
    if (std::isfinite(right.x)) offset = rotate(offset, right, -(target - elevation));
    camera_.eye = camera_.center + offset;
}

void ViewCamera::pan(double dx, double dy, int height) {
    const double scale = worldPerPixel(camera_, height);
    const csg::Vec3 forward = glm::normalize(camera_.center - camera_.eye);
    const csg::Vec3 right = glm::normalize(glm::cross(forward, camera_.up));
    if (!std::isfinite(right.x)) return;
    const csg::Vec3 up = glm::cross(right, forward);
    const csg::Vec3 move = (-dx * right + dy * up) * scale;
    camera_.eye += move;
    camera_.center += move;
}

void ViewCamera::zoom(double steps) {
    const double factor = std::pow(1.0 / 1.15, steps);
    camera_.eye = camera_.center + (camera_.eye - camera_.center) * factor;
}

void ViewCamera::toggleOrthographic() {
    camera_.projection = camera_.projection == render::Projection::Perspective
                             ? render::Projection::Orthographic
                             : render::Projection::Perspective;
}

void ViewCamera::reset() {
    const render::Projection projection = camera_.projection;
    camera_ = initial_;
    camera_.projection = projection;
}

void ViewCamera::frame(const csg::Scene& scene, double aspect) {
    const render::Camera fit = render::frameBounds(scene, aspect);
    const double distance = glm::length(fit.eye - fit.center);
    const csg::Vec3 back = glm::normalize(camera_.eye - camera_.center);
    camera_.center = fit.center;
    // frameBounds fits the default fov; scale the distance for this camera's fov.
    const double fitHalf = std::tan(fit.fov * std::numbers::pi / 360.0);
    const double ourHalf = std::tan(camera_.fov * std::numbers::pi / 360.0);
    camera_.eye = camera_.center + back * (distance * fitHalf / ourHalf);
}

}  // namespace viewer::window
