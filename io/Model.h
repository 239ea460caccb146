// What evaluating a part gives its clients (the command line, the renderer): the CSG tree and
// the scene extras that OpenSCAD itself ignores (camera, lights, background, materials), plus
// the tables that turn a node's opaque csg::Tags back into a material and a source location.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "csg/Tree.h"
#include "io/PngWriter.h"
#include "primitives/base/Math.h"

namespace io {

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
    // Model::textures[texture] tiled over squares of side scale. Both are planar maps.
    Pattern pattern = Pattern::Solid;
    csg::Vec4 color2{0.1, 0.1, 0.1, 1.0};  // RGBA in [0, 1]
    double scale = 1.0;                    // > 0
    int32_t texture = -1;                  // index in Model::textures; -1: none

    bool operator==(const Material&) const = default;
};

// Where a node came from: the statement that created it and the module call chain leading to
// it, e.g. "part() > difference > cylinder". fileIndex indexes Model::files.
struct SourceInfo {
    uint32_t fileIndex = 0;
    uint32_t line = 0;  // 1-based; 0 for the "unknown" entry 0
    uint32_t col = 0;
    uint32_t modulePathIndex = 0;  // indexes Model::modulePaths
};

// A subtree drawn by a modifier: # (highlight, also part of root) or % (background, not part
// of root). node already carries the accumulated transform: it is in world coordinates.
struct MarkedPart {
    csg::NodePtr node;
    uint32_t source = 0;  // Tags::source of the modifier's statement
};

struct Model {
    // The solid: the implicit top-level union. nullptr is the empty solid (an empty file).
    csg::NodePtr root;

    std::optional<Camera> camera;             // nothing: the client frames the whole part
    std::vector<Light> lights;                // empty: the client uses one default light
    std::optional<csg::Vec3> background;      // RGB in [0, 1]; nothing: the client's default
    std::vector<MarkedPart> highlighted;      // # subtrees, for a highlight overlay
    std::vector<MarkedPart> backgroundParts;  // % subtrees, transparent and not solid

    // Indexed by csg::Tags::material; entry 0 is the neutral default Material{}.
    std::vector<Material> materials{Material{}};
    // Images named by material(texture=...), each read once (path as resolved, for
    // messages and for reading a file only once).
    struct Texture {
        std::string path;
        Rgb8Image image;
    };
    std::vector<Texture> textures;
    // Indexed by csg::Tags::source; entry 0 is "unknown" (file "", line 0).
    std::vector<SourceInfo> sources{SourceInfo{}};
    // Every file that was read (the main file first), and the interned module paths.
    std::vector<std::string> files;
    std::vector<std::string> modulePaths{std::string()};

    // Convenience lookups for a Tags::source value; an out-of-range tag reads as entry 0.
    const SourceInfo& source(uint32_t tag) const;
    const std::string& sourceFile(uint32_t tag) const;
    const std::string& modulePath(uint32_t tag) const;
    // "file:line:col" of a tag (just "file" or "" when positions are unknown).
    std::string describeSource(uint32_t tag) const;
};

}  // namespace io
