// The effects plan: which effects a scene can show, derived once before rendering, so the
// tracer casts only the rays that can change a pixel.
//
//   shadow rays   only toward a light with shadows on (per light and globally), non-zero
//                 radiance, and a scene that can occlude it: a single convex solid cannot
//                 shadow its own lit side, so a convex scene casts none;
//   filtering     only when a material in use transmits light: a shadow ray then reads the
//                 spans it crosses (each one filters the light by its material's
//                 transmission) instead of stopping at the first solid;
//   direct light  only on materials with diffuse or specular > 0 (no lights: none at all);
//   specular      only on materials with specular > 0;
//   reflection    only from materials with reflect > 0;
//   refraction    only from materials with transmit > 0;
//   ray tree      a branch ends when its cumulative weight (the product of the reflect or
//                 transmit coefficients along it) falls below minWeight, or at maxDepth
//                 bounces.
#pragma once

#include <string>
#include <vector>

#include "csg/Scene.h"
#include "primitives/base/Json.h"
#include "viewer/render/Look.h"
#include "viewer/render/Materials.h"
#include "viewer/render/Pattern.h"

namespace viewer::render {

// What the user chose (the command line's --no-shadows, --min-weight, --max-depth).
struct PlanSettings {
    bool shadows = true;
    double minWeight = 1.0 / 256.0;  // the seeds' rule: below one 8-bit level it cannot show
    int maxDepth = 10;               // secondary-ray generations after the primary ray
};

struct PlannedLight {
    csg::Vec3 position;  // world coordinates
    csg::Vec3 radiance;  // linear RGB: colour x intensity
    bool shadowRays = false;
    std::string shadowReason;  // why shadow rays are (not) cast toward it
    int modelIndex = -1;       // index in SceneLook::lights; -1 for the default light
};

// One entry per SceneLook::materials entry, indexed by csg::Tags::material.
struct PlannedMaterial {
    ShadingMaterial shading;
    bool used = false;        // some leaf of the scene carries it
    bool direct = false;      // Lambert/Blinn-Phong terms from the lights
    bool specular = false;    // the Blinn-Phong term
    bool reflection = false;  // mirror rays
    bool refraction = false;  // refracted rays (and total internal reflection)
    // Linear RGB share of the light a shadow ray keeps for each span of this material it
    // crosses: transmit times the colour (POV-Ray's filter); 0 for an opaque material.
    csg::Vec3 transmission{0.0};
};

struct EffectsPlan {
    PlanSettings settings;
    std::vector<PlannedLight> lights;  // lights that can light something (radiance > 0)
    int droppedLights = 0;             // lights of the model with zero radiance
    std::vector<PlannedMaterial> materials;
    std::vector<LinearTexture> textures;  // SceneLook::textures, decoded to linear RGB
    csg::Vec3 background{0.0};            // linear RGB
    csg::Vec3 ambientLight{1.0};
    bool convexScene = false;  // the whole solid is one convex set
    // Summaries over the materials in use and the lights.
    bool shadowRays = false, direct = false, specular = false, reflection = false,
         refraction = false;
    // Shadow rays are filtered (a material in use transmits light): they read the spans they
    // cross, where an all-opaque scene asks only whether anything is in the way.
    bool filteredShadows = false;

    // The material of a leaf's tag (an out-of-range tag reads as entry 0, like SceneLook).
    const PlannedMaterial& material(uint32_t tag) const {
        return materials[tag < materials.size() ? tag : 0];
    }
};

// Derives the plan. camera places the default light (one light over the viewer's left
// shoulder) when the model has none.
EffectsPlan makeEffectsPlan(const SceneLook& look, const csg::Node* root, const csg::Scene& scene,
                            const Camera& camera, const PlanSettings& settings);

// The plan as one JSON object (for --stats and `csgray info`).
void writeEffectsPlan(csg::JsonWriter& json, const EffectsPlan& plan);

// True when the tree is certainly one convex set: convex primitives (sphere, box, cylinder
// or cone, half-space) under affine maps and intersections. false means "not known convex".
bool isConvexSolid(const csg::Node& node);

}  // namespace viewer::render
