#include "viewer/window/ViewProbe.h"

#include "viewer/ProbeJson.h"
#include "viewer/render/RenderCamera.h"

namespace viewer::window {

PixelProbe probePixel(const LoadedPart& part, const io::Camera& camera, int width, int height,
                      int x, int y) {
    const csg::Ray ray = render::RenderCamera(camera, width, height).ray(x + 0.5, y + 0.5);
    PixelProbe probe;
    csg::QueryContext ctx;
    const ProbeJson json(part.model, part.scene);
    json.append(probe.json, ray.o, ray.d, ctx);

    csg::Ray query = ray;
    query.tmin = 0.0;
    const std::span<const csg::Span> spans = part.scene.spans(query, ctx);
    if (spans.empty()) {
        probe.summary = "probe: no hit";
        return probe;
    }
    const csg::Hit& first = spans.front().in;
    probe.summary = "probe: " + std::to_string(spans.size()) +
                    (spans.size() == 1 ? " span" : " spans") +
                    ", first hit t=" + std::to_string(first.t).substr(0, 8);
    if (first.isSurface()) {
        const uint32_t source = part.scene.leafTags(first.leaf).source;
        probe.summary += std::string(" ") + primitiveName(part.scene.leafPrimitive(first.leaf)) +
                         " at " + part.model.describeSource(source);
    }
    return probe;
}

}  // namespace viewer::window
