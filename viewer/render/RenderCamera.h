// The camera of a render: the part's camera(...) or one that frames the part, and the primary
// ray through any point of the image plane (pixel coordinates, so sub-pixel samples are free).
#pragma once

#include "csg/Ray.h"
#include "csg/Scene.h"
#include "viewer/render/Look.h"

namespace viewer::render {

// A camera looking at the part's bounds (the leaves' finite bounds clipped by the scene's)
// from OpenSCAD's default direction (front-right, above), far enough that the bounding sphere
// fits an image of the given aspect (width / height) with a 5% margin. A scene with no
// bounded leaf gets Camera{}.
Camera frameBounds(const csg::Scene& scene, double aspect);

class RenderCamera {
public:
    // camera.fov is the vertical field of view; for an orthographic camera the view height
    // is the one the perspective camera would see at the centre's distance.
    RenderCamera(const Camera& camera, int width, int height);

    // The primary ray through image point (x, y): pixel units, origin at the top-left corner,
    // y down, so pixel (i, j) covers [i, i+1] x [j, j+1]. d is unit length, t in world units.
    csg::Ray ray(double x, double y) const { return rayThrough(planeX(x), planeY(y)); }

    // ray(x, y) in halves, for a caller that computes a column's or a row's half once (the
    // renderer's tiles): the image-plane coordinates of x and of y, and the ray through the
    // plane point (sx, sy). Inline, so the divisions left per ray are the normalization's.
    double planeX(double x) const { return (2.0 * x / width_ - 1.0) * halfHeight_ * aspect_; }
    double planeY(double y) const { return (1.0 - 2.0 * y / height_) * halfHeight_; }
    csg::Ray rayThrough(double sx, double sy) const {
        if (orthographic_)
            return csg::Ray{eye_ + sx * right_ + sy * up_, forward_, 0.0, csg::kInfinity};
        return csg::Ray{eye_, glm::normalize(forward_ + sx * right_ + sy * up_), 0.0,
                        csg::kInfinity};
    }

    const csg::Vec3& eye() const { return eye_; }
    const csg::Vec3& right() const { return right_; }
    const csg::Vec3& up() const { return up_; }
    const csg::Vec3& forward() const { return forward_; }
    // Distance from the eye to the camera's centre point (the framing distance).
    double focusDistance() const { return focusDistance_; }

private:
    csg::Vec3 eye_, forward_, right_, up_;
    double halfHeight_;  // tan(fov/2) (perspective) or the world half-height (orthographic)
    double aspect_;
    double focusDistance_;
    bool orthographic_;
    int width_, height_;
};

}  // namespace viewer::render
