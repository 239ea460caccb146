// The Whitted ray tree of one sample: ambient, Lambert diffuse and Blinn-Phong specular from
// point lights, hard shadows, mirror reflection and refraction (Snell's law, total internal
// reflection), each only where the effects plan says it can occur.
//
// Notation: a hit's SurfacePoint normal is the solid's outward unit normal (a difference's
// cut face already flipped), so a ray enters the solid when d . normal < 0 and leaves it when
// d . normal > 0. That is how refraction knows its side: a ray inside a glass part that was
// cut by a difference leaves through the cut face, whose normal points into the cut.
//
// Light through glass: a shadow ray is stopped only by an opaque solid. Each span of a
// transmissive one that it crosses filters the light by the material's transmission (transmit
// times its colour, per channel, as POV-Ray's filter), once per span, without bending it.
//
// Whitted's simplifications, kept on purpose: reflect and transmit are constant weights (no
// Fresnel term), a shadow ray through glass goes straight (no caustics), the medium outside
// every solid is air (ior 1), and a colour's alpha is not transparency (use transmit).
//
// One Tracer per thread: it owns the thread's QueryContext and ray counters. The per-ray path
// allocates nothing and makes no virtual or std::function call.
#pragma once

#include <array>
#include <vector>

#include "csg/Scene.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/RayCounts.h"

namespace viewer::render {

enum class RayKind : uint8_t { Primary, Shadow, Reflection, Refraction };

// A record of the surfaces a ray tree met, in the order they were shaded (tests, debugging).
struct PathLog {
    struct Vertex {
        RayKind kind;      // the kind of the ray that hit this surface
        csg::Vec3 point;   // the hit point
        csg::Vec3 normal;  // outward unit normal of the solid
        bool entering;     // the ray was entering the solid (d . normal < 0)
        uint32_t leaf;
    };
    static constexpr int kCapacity = 64;
    std::array<Vertex, kCapacity> vertices;
    int count = 0;
};

class Tracer {
public:
    Tracer(const csg::Scene& scene, const EffectsPlan& plan)
        : scene_(scene), plan_(plan), occluders_(plan.lights.size()) {}

    // The linear RGB radiance along a primary ray (unit d), background included.
    csg::Vec3 tracePrimary(const csg::Ray& ray);

    RayCounts rays;
    csg::QueryContext context;
    PathLog* log = nullptr;  // when set, every shaded hit is appended (until it is full)

private:
    csg::Vec3 trace(const csg::Ray& ray, RayKind kind, int depth, double weight);
    // albedo: the material's colour at this point (its pattern already looked up).
    csg::Vec3 directLight(const PlannedMaterial& m, const csg::Vec3& albedo, const csg::Vec3& point,
                          const csg::Vec3& pointError, const csg::Vec3& n, const csg::Vec3& view);
    // The colour of a patterned material at a hit of `leaf` (Pattern.h's planar maps).
    csg::Vec3 patternColor(const ShadingMaterial& s, const csg::SurfacePoint& surface,
                           uint32_t leaf);
    // The share of the light (linear RGB) that reaches the end of a shadow ray through the
    // spans it crosses: 0 at the first opaque span.
    csg::Vec3 lightThrough(const csg::Ray& shadow);

    const csg::Scene& scene_;
    const EffectsPlan& plan_;
    std::vector<csg::ObjectCache> occluders_;  // per light: what last shadowed this thread
    // The planar leaf (a half-space) whose pattern was looked up last, and its plane frame: a
    // plane's normal, so its frame, is the same at every hit (a checkered floor is one leaf).
    uint32_t frameLeaf_ = UINT32_MAX;
    PlaneFrame frame_{};
};

}  // namespace viewer::render
