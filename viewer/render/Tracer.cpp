#include "viewer/render/Tracer.h"

#include <cmath>
#include <variant>

#include "viewer/render/SecondaryOrigin.h"

namespace viewer::render {

namespace {

bool positive(const csg::Vec3& c) {
    return c.r > 0.0 || c.g > 0.0 || c.b > 0.0;
}

}  // namespace

csg::Vec3 Tracer::tracePrimary(const csg::Ray& ray) {
    ++rays.primary;
    return trace(ray, RayKind::Primary, 0, 1.0);
}

csg::Vec3 Tracer::trace(const csg::Ray& ray, RayKind kind, int depth, double weight) {
    const std::optional<csg::Hit> hit = scene_.closest(ray, context);
    if (!hit) return plan_.background;
    const csg::SurfacePoint surface = scene_.surface(ray, *hit);
    const PlannedMaterial& m = plan_.material(scene_.leafTags(hit->leaf).material);
    const ShadingMaterial& s = m.shading;

    // The side the ray comes from: n faces it, so lighting and offsets use one rule for rays
    // outside (entering) and inside (leaving) the solid.
    const csg::Vec3 dir = glm::normalize(ray.d);
    const bool entering = glm::dot(ray.d, surface.normal) < 0.0;
    const csg::Vec3 n = entering ? surface.normal : -surface.normal;
    const csg::Vec3 error = hitPointError(ray, hit->t);
    if (log && log->count < PathLog::kCapacity)
        log->vertices[log->count++] = {kind, surface.point, surface.normal, entering, hit->leaf};

    csg::Vec3 color(0.0);
    // Local terms belong to the surface as seen from outside; the inside face of a glass part
    // is seen only through refraction, which carries its own light.
    if (entering || !m.refraction) {
        const csg::Vec3 albedo =
            s.pattern == Pattern::Solid ? s.color : patternColor(s, surface, hit->leaf);
        color += s.ambient * albedo * plan_.ambientLight;
        if (m.direct) color += directLight(m, albedo, surface.point, error, n, -dir);
    }
    if (depth >= plan_.settings.maxDepth) return color;

    // Mirror reflection, only while the branch still weighs enough to show.
    if (m.reflection && weight * s.reflect >= plan_.settings.minWeight) {
        const csg::Vec3 r = dir - 2.0 * glm::dot(dir, n) * n;
        const csg::Ray reflected{offsetRayOrigin(surface.point, error, n, r), r, 0.0,
                                 csg::kInfinity};
        ++rays.reflection;
        color += s.reflect * trace(reflected, RayKind::Reflection, depth + 1, weight * s.reflect);
    }

    // Refraction by Snell's law, n1 sin(i) = n2 sin(t), against air (ior 1) outside the solid;
    // past the critical angle the transmitted share is totally internally reflected.
    if (m.refraction && weight * s.transmit >= plan_.settings.minWeight) {
        const double eta = entering ? 1.0 / s.ior : s.ior;  // n1 / n2
        const double cosI = -glm::dot(dir, n);
        const double k = 1.0 - eta * eta * (1.0 - cosI * cosI);
        const csg::Vec3 t =
            k < 0.0 ? dir + 2.0 * cosI * n : eta * dir + (eta * cosI - std::sqrt(k)) * n;
        const csg::Ray refracted{offsetRayOrigin(surface.point, error, n, t), t, 0.0,
                                 csg::kInfinity};
        ++rays.refraction;
        color += s.transmit * trace(refracted, RayKind::Refraction, depth + 1, weight * s.transmit);
    }
    return color;
}

csg::Vec3 Tracer::patternColor(const ShadingMaterial& s, const csg::SurfacePoint& surface,
                               uint32_t leaf) {
    if (leaf != frameLeaf_ && csg::isPlanar(scene_.leafPrimitive(leaf))) {
        frameLeaf_ = leaf;
        frame_ = planeFrame(surface.normal);
    }
    const csg::Vec2 uv =
        leaf == frameLeaf_
            ? csg::Vec2(glm::dot(surface.point, frame_.u), glm::dot(surface.point, frame_.v))
            : planarCoordinates(surface.point, surface.normal, false);
    if (s.pattern == Pattern::Checker)
        return checkerParity(uv, s.inverseScale) ? s.color2 : s.color;
    return sampleTexture(plan_.textures[size_t(s.texture)], uv, s.inverseScale);
}

csg::Vec3 Tracer::lightThrough(const csg::Ray& shadow) {
    csg::Vec3 through(1.0);
    for (const csg::Span& span : scene_.spans(shadow, context)) {
        // The regularized union's span: its material is the one the ray enters by (or leaves
        // by, when it starts inside); a span that either end makes opaque blocks, so an opaque
        // solid that cuts into glass is not seen through.
        const PlannedMaterial& in = plan_.material(scene_.leafTags(span.in.leaf).material);
        const PlannedMaterial& out = plan_.material(scene_.leafTags(span.out.leaf).material);
        if (!positive(in.transmission) || !positive(out.transmission)) return csg::Vec3(0.0);
        through *= span.in.isSurface() ? in.transmission : out.transmission;
    }
    return through;
}

csg::Vec3 Tracer::directLight(const PlannedMaterial& m, const csg::Vec3& albedo,
                              const csg::Vec3& point, const csg::Vec3& pointError,
                              const csg::Vec3& n, const csg::Vec3& view) {
    const ShadingMaterial& s = m.shading;
    csg::Vec3 sum(0.0);
    for (size_t i = 0; i < plan_.lights.size(); ++i) {
        const PlannedLight& light = plan_.lights[i];
        const csg::Vec3 toLight = light.position - point;
        const double nDotL = glm::dot(n, toLight);
        if (nDotL <= 0.0) continue;  // the light is behind the surface
        csg::Vec3 radiance = light.radiance;
        if (light.shadowRays) {
            // t runs from the offset origin (0) to the light (1): tmax is the light itself,
            // and occluded() computes no point or normal.
            const csg::Vec3 origin = offsetRayOrigin(point, pointError, n, toLight);
            const csg::Ray shadow{origin, light.position - origin, 0.0, 1.0};
            ++rays.shadow;
            if (plan_.filteredShadows) {
                const csg::Vec3 through = lightThrough(shadow);
                if (!positive(through)) continue;
                radiance *= through;
            } else if (scene_.occluded(shadow, context, occluders_[i])) {
                continue;
            }
        }
        const double distance = glm::length(toLight);
        const csg::Vec3 l = toLight / distance;
        csg::Vec3 term = (s.diffuse * (nDotL / distance)) * albedo;
        if (m.specular) {
            // Blinn-Phong: the half vector between light and viewer against the normal.
            const csg::Vec3 h = glm::normalize(l + view);
            const double nDotH = glm::dot(n, h);
            if (nDotH > 0.0) term += csg::Vec3(s.specular * highlight(nDotH, s));
        }
        sum += radiance * term;
    }
    return sum;
}

}  // namespace viewer::render
