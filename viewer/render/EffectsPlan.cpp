#include "viewer/render/EffectsPlan.h"

#include "viewer/render/Color.h"
#include "viewer/render/RenderCamera.h"

namespace viewer::render {

namespace {

bool positive(const csg::Vec3& c) {
    return c.r > 0.0 || c.g > 0.0 || c.b > 0.0;
}

// Over the viewer's left shoulder, a little behind the eye: the usual studio key light.
csg::Vec3 defaultLightPosition(const Camera& camera) {
    const RenderCamera frame(camera, 1, 1);
    const double d = frame.focusDistance();
    return frame.eye() + d * (0.5 * frame.up() - 0.3 * frame.right() - 0.2 * frame.forward());
}

}  // namespace

bool isConvexSolid(const csg::Node& node) {
    switch (node.op) {
        case csg::Op::Leaf:
            return csg::isConvex(node.primitive);
        case csg::Op::Intersection:
            return node.left && node.right && isConvexSolid(*node.left) &&
                   isConvexSolid(*node.right);
        case csg::Op::Union:
            // A union with one operand (a group of one child) is that operand.
            if (node.left && !node.right) return isConvexSolid(*node.left);
            if (node.right && !node.left) return isConvexSolid(*node.right);
            return false;
        case csg::Op::Difference:
            return false;
    }
    return false;
}

EffectsPlan makeEffectsPlan(const SceneLook& look, const csg::Node* root, const csg::Scene& scene,
                            const Camera& camera, const PlanSettings& settings) {
    EffectsPlan plan;
    plan.settings = settings;
    plan.background = srgbToLinear(look.background ? *look.background : kDefaultBackgroundSrgb);
    plan.convexScene = scene.leafCount() == 0 || (root && isConvexSolid(*root));

    // Materials: which are carried by a leaf, and which terms each one has.
    plan.materials.resize(look.materials.empty() ? 1 : look.materials.size());
    for (size_t i = 0; i < look.materials.size(); ++i)
        plan.materials[i].shading = shadingMaterial(look.materials[i]);
    // Textures are decoded here, once, so the tracer only looks texels up.
    plan.textures.reserve(look.textures.size());
    for (const SceneLook::Texture& t : look.textures)
        plan.textures.push_back(LinearTexture::fromSrgb(t.image));
    for (PlannedMaterial& m : plan.materials)
        if (m.shading.texture >= int32_t(plan.textures.size()))
            m.shading.pattern = Pattern::Solid;  // a stale index: never read past the table
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf) {
        const uint32_t tag = scene.leafTags(leaf).material;
        plan.materials[tag < plan.materials.size() ? tag : 0].used = true;
    }

    // Lights: the model's, or one default light; a light with no radiance lights nothing.
    std::vector<Light> lights = look.lights;
    const bool defaultLight = lights.empty();
    if (defaultLight) lights.push_back(Light{defaultLightPosition(camera)});
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        PlannedLight p;
        p.position = light.position;
        p.radiance = light.color * light.intensity;
        p.modelIndex = defaultLight ? -1 : int(i);
        if (!positive(p.radiance)) {
            ++plan.droppedLights;
            continue;
        }
        if (!settings.shadows) {
            p.shadowReason = "shadows off (--no-shadows)";
        } else if (!light.shadows) {
            p.shadowReason = "shadows off for this light";
        } else if (plan.convexScene) {
            p.shadowReason = "the scene is one convex solid: nothing shadows a lit point";
        } else {
            p.shadowRays = true;
            p.shadowReason = "the scene can occlude the light";
        }
        plan.lights.push_back(p);
    }

    const bool lit = !plan.lights.empty();
    bool anyShadowLight = false;
    for (const PlannedLight& l : plan.lights) anyShadowLight |= l.shadowRays;
    for (PlannedMaterial& m : plan.materials) {
        const ShadingMaterial& s = m.shading;
        m.specular = lit && s.specular > 0.0;
        m.direct = lit && (s.diffuse > 0.0 || m.specular);
        m.reflection = s.reflect > 0.0 && settings.maxDepth > 0;
        m.refraction = s.transmit > 0.0 && settings.maxDepth > 0;
        // Light reaches through glass whatever the ray tree's depth: the shadow ray is cast
        // from the lit point, not from the glass.
        if (s.transmit > 0.0) m.transmission = s.transmit * s.color;
        if (!m.used) continue;
        plan.filteredShadows |= positive(m.transmission);
        plan.direct |= m.direct;
        plan.specular |= m.specular;
        plan.reflection |= m.reflection;
        plan.refraction |= m.refraction;
    }
    plan.shadowRays = plan.direct && anyShadowLight;
    plan.filteredShadows &= plan.shadowRays;
    return plan;
}

void writeEffectsPlan(csg::JsonWriter& json, const EffectsPlan& plan) {
    json.beginObject();
    json.key("shadowRays").value(plan.shadowRays);
    json.key("directLight").value(plan.direct);
    json.key("specular").value(plan.specular);
    json.key("reflection").value(plan.reflection);
    json.key("refraction").value(plan.refraction);
    json.key("filteredShadows").value(plan.filteredShadows);
    json.key("convexScene").value(plan.convexScene);
    json.key("minWeight").value(plan.settings.minWeight);
    json.key("maxDepth").value(plan.settings.maxDepth);
    json.key("globalShadows").value(plan.settings.shadows);
    json.key("lights").beginArray();
    for (const PlannedLight& l : plan.lights) {
        json.beginObject();
        json.key("model").value(l.modelIndex >= 0 ? "light" : "default");
        if (l.modelIndex >= 0) json.key("index").value(l.modelIndex);
        json.key("position").vec(l.position, 3);
        json.key("radiance").vec(l.radiance, 3);
        json.key("shadowRays").value(l.shadowRays);
        json.key("why").value(l.shadowReason);
        json.endObject();
    }
    json.endArray();
    json.key("droppedLights").value(plan.droppedLights);
    json.key("materials").beginArray();
    for (size_t i = 0; i < plan.materials.size(); ++i) {
        const PlannedMaterial& m = plan.materials[i];
        json.beginObject();
        json.key("index").value(uint64_t(i));
        json.key("used").value(m.used);
        json.key("direct").value(m.direct);
        json.key("specular").value(m.specular);
        json.key("reflection").value(m.reflection);
        json.key("refraction").value(m.refraction);
        json.key("transmission").vec(m.transmission, 3);
        json.endObject();
    }
    json.endArray();
    json.endObject();
}

}  // namespace viewer::render
