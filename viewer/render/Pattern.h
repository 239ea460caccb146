// Surface patterns (material(pattern=...)): a checker of two colours and a tiled PNG texture,
// both planar maps evaluated at a hit point in world coordinates.
//
// Notation: (u, v) are the pattern's 2-D coordinates in world units. A half-space maps with
// its plane's own orthonormal frame, so its squares are squares however the plane is tilted;
// any other surface projects onto the coordinate plane most facing its normal (x-y when the
// normal is mostly z, y-z when mostly x, x-z when mostly y). Squares are 2-D on purpose: a
// 3-D checker (POV-Ray's) flickers on a plane that lies on a square boundary, such as y = -1.
#pragma once

#include <vector>

#include "primitives/base/Math.h"
#include "viewer/render/PngWriter.h"

namespace viewer::render {

// A texture decoded once to linear RGB, so sampling is a lookup and a blend.
struct LinearTexture {
    int width = 0, height = 0;
    std::vector<float> rgb;  // row-major, top row first, 3 floats per texel

    static LinearTexture fromSrgb(const Rgb8Image& image);
};

// (u, v) of point p on a surface with unit normal n (see the notation above).
csg::Vec2 planarCoordinates(const csg::Vec3& p, const csg::Vec3& n, bool halfSpace);

// The orthonormal axes a half-space's plane with unit normal n is mapped with:
// planarCoordinates(p, n, true) is (p . u, p . v). The same for n and -n, so a renderer may
// keep it per half-space (whose normal is the same at every hit).
struct PlaneFrame {
    csg::Vec3 u, v;
};
PlaneFrame planeFrame(const csg::Vec3& n);

// Which of the two checker colours covers (u, v): 0 or 1, alternating every `scale`.
int checkerParity(const csg::Vec2& uv, double inverseScale);

// The texture tiled with one copy per `scale` x `scale` square, u to the right and v up
// (the image's top row at the top of the square), bilinear between texel centres.
csg::Vec3 sampleTexture(const LinearTexture& texture, const csg::Vec2& uv, double inverseScale);

}  // namespace viewer::render
