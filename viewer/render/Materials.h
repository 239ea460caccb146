// Shading materials: Material (sRGB colour, unitless coefficients) turned into what the
// tracer reads per hit (linear colour), and the seed thesis' material classes as presets.
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "primitives/base/Math.h"
#include "viewer/render/Look.h"

namespace viewer::render {

// What the tracer needs of a material, colour already in linear light.
struct ShadingMaterial {
    csg::Vec3 color{1.0};  // linear RGB: tints ambient and diffuse light
    double ambient = 0.0;
    double diffuse = 0.0;
    double specular = 0.0;  // Blinn-Phong weight; the highlight has the light's colour
    double shininess = 1.0;
    // shininess when it is a whole number in [1, kMaxSquaringExponent], else 0 (see highlight).
    uint32_t wholeShininess = 0;
    double reflect = 0.0;   // weight of the mirrored ray
    double transmit = 0.0;  // weight of the refracted ray
    double ior = 1.0;       // index of refraction against the surrounding air (1.0)
    // A pattern replaces color by one looked up at the hit (viewer/render/Pattern.h).
    Pattern pattern = Pattern::Solid;
    csg::Vec3 color2{0.0};      // linear RGB: the checker's other colour
    double inverseScale = 1.0;  // 1 / the pattern's square size in world units
    int32_t texture = -1;       // index in EffectsPlan::textures (SceneLook::textures)
};

ShadingMaterial shadingMaterial(const Material& m);

// Exponents up to this are raised by squaring (at most 2 log2 of it multiplications).
inline constexpr uint32_t kMaxSquaringExponent = 1024;

// The Blinn-Phong highlight cos^shininess for cos in [0, 1]. A whole exponent (the usual
// case) is raised by squaring, a few multiplications instead of a std::pow call, which showed
// in csg_grid's profile (bench/README.md at dabd601); each squaring doubles the relative error, so
// it stays below shininess * 2^-53 (1e-13 at the largest), far below a float pixel's 2^-24.
inline double highlight(double cos, const ShadingMaterial& s) {
    uint32_t e = s.wholeShininess;
    if (e == 0) return std::pow(cos, s.shininess);
    double result = 1.0;
    for (double power = cos;; power *= power) {
        if (e & 1u) result *= power;
        if ((e >>= 1) == 0) return result;
    }
}

// The table the tracer indexes by csg::Tags::material (same order as SceneLook::materials).
std::vector<ShadingMaterial> shadingMaterials(const SceneLook& look);

// The material classes of the seed thesis. The part language has no preset selector (its
// material() takes the coefficients), so a part writes a class out with these values, e.g.
// a mirror is material(ambient=0, diffuse=0, specular=0.5, shininess=200, reflect=0.9).
// Colour is left at Material's default; only the coefficients define the class.
enum class MaterialClass {
    BlackBody,    // absorbs everything: all coefficients 0 (renders black)
    Ambient,      // self-coloured, unlit: ambient 1, nothing else
    Diffuse,      // matte: ambient 0.1, diffuse 0.9
    Specular,     // glossy plastic: ambient 0.1, diffuse 0.6, specular 0.5, shininess 64
    Mirror,       // ambient 0, diffuse 0.05, specular 0.5, shininess 200, reflect 0.9
    Transparent,  // glass: ambient 0, diffuse 0.05, specular 0.5, shininess 200,
                  // reflect 0.05, transmit 0.9, ior 1.5
};

Material materialPreset(MaterialClass kind);
std::string_view materialClassName(MaterialClass kind);

}  // namespace viewer::render
