#include "viewer/cli/ProbeJson.h"

#include <cmath>
#include <variant>

#include "primitives/base/Json.h"

namespace viewer {

ProbeJson::ProbeJson(const io::Model& model, const csg::Scene& scene) : scene_(scene) {
    leafObjects_.reserve(scene.leafCount());
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf) {
        const uint32_t source = scene.leafTags(leaf).source;
        std::string text;
        csg::JsonWriter json(text);
        json.beginObject()
            .key("leaf")
            .value(leaf)
            .key("primitive")
            .value(csg::primitiveName(scene.leafPrimitive(leaf)))
            .key("module")
            .value(model.modulePath(source))
            .key("source")
            .value(model.describeSource(source))
            .endObject();
        leafObjects_.push_back(std::move(text));
    }
}

void ProbeJson::append(std::string& out, const csg::Vec3& origin, const csg::Vec3& d,
                       csg::QueryContext& ctx) const {
    const csg::Ray ray{origin, d, 0.0, csg::kInfinity};
    csg::JsonWriter json(out);
    json.beginObject();
    json.key("ray").beginObject().key("origin").vec(origin, 3).key("dir").vec(d, 3).endObject();
    json.key("spans").beginArray();

    auto writeEnd = [&](const csg::Hit& hit, bool isIn) {
        json.beginObject();
        json.key("t").value(hit.t);
        if (hit.isSurface()) {
            const csg::SurfacePoint sp = scene_.surface(ray, hit);
            json.key("point").vec(sp.point, 3).key("normal").vec(sp.normal, 3);
        } else {
            // A clipped end: the ray's own start (inside a solid) or its endless far end.
            if (std::isfinite(hit.t)) {
                json.key("point").vec(ray.at(hit.t), 3);
            } else {
                json.key("point").null();
            }
            json.key("normal").null();
            json.key(isIn ? "inside" : "unbounded").value(true);
        }
        json.key("object");
        if (hit.leaf < leafObjects_.size()) {
            json.raw(leafObjects_[hit.leaf]);
        } else {
            json.null();
        }
        json.endObject();
    };

    for (const csg::Span& span : scene_.spans(ray, ctx)) {
        json.beginObject();
        json.key("in");
        writeEnd(span.in, true);
        json.key("out");
        writeEnd(span.out, false);
        json.endObject();
    }
    json.endArray().endObject();
}

}  // namespace viewer
