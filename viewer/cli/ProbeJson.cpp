#include "viewer/cli/ProbeJson.h"

#include <cmath>
#include <variant>

#include "primitives/base/Json.h"

namespace viewer {

ProbeJson::ProbeJson(const io::Model& model, const csg::Scene& scene)
    : model_(model),
      scene_(scene),
      formatted_(std::make_unique<std::once_flag[]>(scene.leafCount())),
      leafObjects_(scene.leafCount()) {}

const std::string& ProbeJson::leafObject(uint32_t leaf) const {
    std::call_once(formatted_[leaf], [&] {
        const uint32_t source = scene_.leafTags(leaf).source;
        csg::JsonWriter json(leafObjects_[leaf]);
        json.beginObject()
            .key("leaf")
            .value(leaf)
            .key("primitive")
            .value(csg::primitiveName(scene_.leafPrimitive(leaf)))
            .key("module")
            .value(model_.modulePath(source))
            .key("source")
            .value(model_.describeSource(source))
            .endObject();
    });
    return leafObjects_[leaf];
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
            json.raw(leafObject(hit.leaf));
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
