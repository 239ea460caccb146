// The interactive camera of `csgray view`: an render::Camera (so a view renders exactly like
// `csgray render` with that camera) plus the mouse gestures that move it. Orbit turns the eye
// around the centre (yaw about the camera's up axis, pitch about its right axis, clamped short
// of the poles so up stays defined); pan slides eye and centre together in the image plane;
// zoom scales the eye-centre distance (and so the orthographic view height too).
#pragma once

#include "csg/Scene.h"
#include "io/Model.h"

namespace viewer::window {

class ViewCamera {
public:
    // initial is what R restores: the part's camera(...) or the framing camera.
    explicit ViewCamera(const render::Camera& initial) : initial_(initial), camera_(initial) {}

    const render::Camera& camera() const { return camera_; }

    // dx, dy in pixels of a window of the given height; dragging right turns the part right.
    void orbit(double dx, double dy, int height);
    // Moves the part with the mouse: dx, dy in pixels of a window of the given height.
    void pan(double dx, double dy, int height);
    // steps > 0 moves closer (each step 1/1.15 of the distance).
    void zoom(double steps);
    void toggleOrthographic();
    // R: back to the initial camera (keeping the current projection).
    void reset();
    // F: keeps the view direction and projection, centres the part's bounds and fits them.
    void frame(const csg::Scene& scene, double aspect);
    // A reload: the new part's initial camera becomes what R restores; the view stays.
    void setInitial(const render::Camera& initial) { initial_ = initial; }

private:
    render::Camera initial_;
    render::Camera camera_;
};

}  // namespace viewer::window
