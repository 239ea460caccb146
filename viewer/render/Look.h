// What the renderer is told about a scene besides its solid: the camera, the lights and the
// materials that a leaf's csg::Tags::material selects. The part language fills these in
// (io::Model); the renderer, the window and the mesh writers read them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "primitives/base/Math.h"
#include "viewer/render/PngWriter.h"

namespace viewer::render {

enum class Projection : uint8_t { Perspective, Orthographic };

// camera(eye, center, up, fov, projection). fov is the vertical field of view in degrees.
struct Camera {
    csg::Vec3 eye{0.0, -10.0, 0.0};
    csg::Vec3 center{0.0};
    csg::Vec3 up{0.0, 0.0, 1.0};
    double fov = 45.0;
    Projection projection = Projection::Perspective;
};

// light(position, color, intensity, shadows): a point light in world coordinates.
struct Light {
    csg::Vec3 position{0.0};
    csg::Vec3 color{1.0};  // linear RGB in [0, 1]
    double intensity = 1.0;
    bool shadows = true;
};

// What colours a surface: color alone, or a planar pattern over it (material(pattern=...)).
enum class Pattern : uint8_t { Solid, Checker, Texture };

// A shading material (material(...) and color(...)); coefficients are unitless weights.
struct Material {
    csg::Vec4 color{0.976, 0.843, 0.173, 1.0};  // RGBA in [0, 1]; OpenSCAD's default yellow
    double ambient = 0.1;
    double diffuse = 0.7;
    double specular = 0.2;
    double shininess = 32.0;  // Phong exponent
    double reflect = 0.0;     // fraction of light mirrored
    double transmit = 0.0;    // fraction of light refracted through
    double ior = 1.5;         // index of refraction (used when transmit > 0)
    // Checker: squares of side scale (world units) alternating color and color2. Texture:
    // SceneLook::textures[texture] tiled over squares of side scale. Both are planar maps.
    Pattern pattern = Pattern::Solid;
    csg::Vec4 color2{0.1, 0.1, 0.1, 1.0};  // RGBA in [0, 1]
    double scale = 1.0;                    // > 0
    int32_t texture = -1;                  // index in SceneLook::textures; -1: none

    bool operator==(const Material&) const = default;
};

// Everything the renderer needs of a scene besides its compiled solid.
struct SceneLook {
    std::optional<Camera> camera;         // nothing: the client frames the whole part
    std::vector<Light> lights;            // empty: the client uses one default light
    std::optional<csg::Vec3> background;  // RGB in [0, 1]; nothing: the client's default
    // Indexed by csg::Tags::material; entry 0 is the neutral default Material{}.
    std::vector<Material> materials{Material{}};
    // Images named by material(texture=...), each read once (path as resolved, for
    // messages and for reading a file only once).
    struct Texture {
        std::string path;
        Rgb8Image image;
    };
    std::vector<Texture> textures;
};

}  // namespace viewer::render
