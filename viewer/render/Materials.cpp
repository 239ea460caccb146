#include "viewer/render/Materials.h"

#include "viewer/render/Color.h"

namespace viewer::render {

ShadingMaterial shadingMaterial(const Material& m) {
    ShadingMaterial s;
    s.color = srgbToLinear(csg::Vec3(m.color));
    s.ambient = m.ambient;
    s.diffuse = m.diffuse;
    s.specular = m.specular;
    s.shininess = m.shininess;
    if (m.shininess >= 1.0 && m.shininess <= kMaxSquaringExponent &&
        m.shininess == std::floor(m.shininess))
        s.wholeShininess = uint32_t(m.shininess);
    s.reflect = m.reflect;
    s.transmit = m.transmit;
    s.ior = m.ior > 0.0 ? m.ior : 1.0;  // the language rejects ior <= 0; stay finite anyway
    s.pattern = m.pattern;
    s.color2 = srgbToLinear(csg::Vec3(m.color2));
    s.inverseScale = m.scale > 0.0 ? 1.0 / m.scale : 1.0;  // the language rejects scale <= 0
    s.texture = m.texture;
    if (s.pattern == Pattern::Texture && s.texture < 0) s.pattern = Pattern::Solid;
    return s;
}

std::vector<ShadingMaterial> shadingMaterials(const SceneLook& look) {
    std::vector<ShadingMaterial> table;
    table.reserve(look.materials.size());
    for (const Material& m : look.materials) table.push_back(shadingMaterial(m));
    if (table.empty()) table.push_back(shadingMaterial(Material{}));
    return table;
}

Material materialPreset(MaterialClass kind) {
    Material m;
    m.ambient = m.diffuse = m.specular = m.reflect = m.transmit = 0.0;
    m.shininess = 1.0;
    m.ior = 1.0;
    switch (kind) {
        case MaterialClass::BlackBody:
            break;
        case MaterialClass::Ambient:
            m.ambient = 1.0;
            break;
        case MaterialClass::Diffuse:
            m.ambient = 0.1;
            m.diffuse = 0.9;
            break;
        case MaterialClass::Specular:
            m.ambient = 0.1;
            m.diffuse = 0.6;
            m.specular = 0.5;
            m.shininess = 64.0;
            break;
        case MaterialClass::Mirror:
            m.diffuse = 0.05;
            m.specular = 0.5;
            m.shininess = 200.0;
            m.reflect = 0.9;
            break;
        case MaterialClass::Transparent:
            m.diffuse = 0.05;
            m.specular = 0.5;
            m.shininess = 200.0;
            m.reflect = 0.05;
            m.transmit = 0.9;
            m.ior = 1.5;
            break;
    }
    return m;
}

std::string_view materialClassName(MaterialClass kind) {
    switch (kind) {
        case MaterialClass::BlackBody:
            return "black body";
        case MaterialClass::Ambient:
            return "ambient";
        case MaterialClass::Diffuse:
            return "diffuse";
        case MaterialClass::Specular:
            return "specular";
        case MaterialClass::Mirror:
            return "mirror";
        case MaterialClass::Transparent:
            return "transparent";
    }
    return "?";
}

}  // namespace viewer::render
