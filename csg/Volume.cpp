#include "csg/Volume.h"

#include <algorithm>
#include <vector>

#include "primitives/base/ParallelFor.h"

namespace csg {

double volume(const Scene& scene, int resolution, int threads) {
    const Bounds3 box = scene.bounds();
    if (box.empty()) return 0.0;
    if (!box.finite()) return kInfinity;
    const Vec3 size = box.extent();
    const double cellX = size.x / resolution, cellY = size.y / resolution;
    // Rows on every worker, each summed on its own (to keep the running total's rounding
    // small), then added in row order: the same sum for any thread count.
    const int workers = resolveThreads(threads);
    std::vector<WorkerSlot<QueryContext>> contexts(static_cast<size_t>(workers));
    std::vector<double> rows(static_cast<size_t>(std::max(resolution, 0)), 0.0);
    parallelFor(rows.size(), workers, [&](int worker, uint64_t j) {
        QueryContext& ctx = contexts[size_t(worker)].value;
        double row = 0.0;
        for (int i = 0; i < resolution; ++i) {
            // Start below the box so every span is entered from outside; d is unit along z.
            const Ray ray{{box.lo.x + (i + 0.5) * cellX, box.lo.y + (double(j) + 0.5) * cellY,
                           box.lo.z - 1.0},
                          {0.0, 0.0, 1.0}};
            for (const Span& s : scene.spans(ray, ctx)) row += s.out.t - s.in.t;
        }
        rows[j] = row;
    });
    double total = 0.0;
    for (const double row : rows) total += row;
    return total * cellX * cellY;
}

}  // namespace csg
