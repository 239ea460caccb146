#include "viewer/render/PreviewRender.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "primitives/base/ParallelFor.h"
#include "viewer/render/Color.h"
#include "viewer/render/RenderCamera.h"

namespace viewer::render {

Rgb8Image renderPreview(const SceneLook& look, const csg::Scene& scene, int width, int height,
                        int threads) {
    Rgb8Image image(width, height);
    const double aspect = double(width) / double(height);
    const Camera camera = look.camera ? *look.camera : frameBounds(scene, aspect);
    const RenderCamera rays(camera, width, height);
    const csg::Vec3 background = look.background ? *look.background : kDefaultBackgroundSrgb;
    uint8_t backgroundPixel[3];
    for (int i = 0; i < 3; ++i) backgroundPixel[i] = uint8_t(std::lround(background[i] * 255.0));

    // Linear colors per material, looked up by the leaf's tag.
    std::vector<csg::Vec3> linearColors;
    for (const Material& m : look.materials)
        linearColors.push_back(render::srgbToLinear(csg::Vec3(m.color)));

    // One query context per worker; every row is written before the image is handed back.
    std::vector<csg::WorkerSlot<csg::QueryContext>> contexts(static_cast<size_t>(threads));
    csg::parallelFor(uint64_t(height), threads, [&](int worker, uint64_t rowIndex) {
        csg::QueryContext& ctx = contexts[size_t(worker)].value;
        const int y = int(rowIndex);
        uint8_t* row = image.row(y);
        for (int x = 0; x < width; ++x) {
            uint8_t* px = row + 3 * x;
            const csg::Ray ray = rays.ray(x + 0.5, y + 0.5);
            const std::optional<csg::Hit> hit = scene.closest(ray, ctx);
            if (!hit || !hit->isSurface()) {
                std::copy(backgroundPixel, backgroundPixel + 3, px);
                continue;
            }
            const csg::SurfacePoint sp = scene.surface(ray, *hit);
            const uint32_t material = scene.leafTags(hit->leaf).material;
            const csg::Vec3& color = linearColors[material < linearColors.size() ? material : 0];
            // Headlight: the light sits at the eye, so the cosine is with the view ray.
            // abs() lights a back face seen from inside the solid rather than blacking it.
            const double lambert = std::abs(glm::dot(sp.normal, ray.d));
            const double shade = 0.15 + 0.85 * lambert;
            for (int i = 0; i < 3; ++i) px[i] = render::linearToSrgb8(color[i] * shade);
        }
    });
    return image;
}

}  // namespace viewer::render
