#include "csg/Volume.h"

namespace csg {

double volume(const Scene& scene, int resolution) {
    const Bounds3 box = scene.bounds();
    if (box.empty()) return 0.0;
    if (!box.finite()) return kInfinity;
    const Vec3 size = box.extent();
    const double cellX = size.x / resolution, cellY = size.y / resolution;
    QueryContext ctx;
    double total = 0.0;
    for (int j = 0; j < resolution; ++j) {
        double row = 0.0;  // summed per row to keep the running total's rounding small
        for (int i = 0; i < resolution; ++i) {
            // Start below the box so every span is entered from outside; d is unit along z.
            const Ray ray{
                {box.lo.x + (i + 0.5) * cellX, box.lo.y + (j + 0.5) * cellY, box.lo.z - 1.0},
                {0.0, 0.0, 1.0}};
            for (const Span& s : scene.spans(ray, ctx)) row += s.out.t - s.in.t;
        }
        total += row;
    }
    return total * cellX * cellY;
}

}  // namespace csg
