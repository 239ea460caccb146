#include "csg/Volume.h"

#include <algorithm>
#include <cmath>
#include <variant>
#include <vector>

#include "primitives/Primitives.h"
#include "primitives/base/ParallelFor.h"

namespace csg {

VolumeAxis volumeLineAxis(const Scene& scene) {
    // A line's solve through a twisted extrusion grows with the twist it sweeps: the turns
    // times the cosine between the line and the extrusion's axis (a level line meets one
    // section, a prism's problem). Each axis is charged that cosine weighted by the turns.
    double charge[3] = {0.0, 0.0, 0.0};
    for (uint32_t leaf = 0; leaf < scene.leafCount(); ++leaf) {
        const auto* e = std::get_if<Extrusion>(&scene.leafPrimitive(leaf));
        if (!e || e->kind != Extrusion::Kind::Linear || !e->twisted || e->twist == 0.0) continue;
        const Vec3 axis = Mat3(scene.leafWorldFromLocal(leaf)) * Vec3(0.0, 0.0, 1.0);
        const double length = glm::length(axis);
        if (!(length > 0.0)) continue;
        for (int k = 0; k < 3; ++k) charge[k] += std::abs(e->twist) * std::abs(axis[k]) / length;
    }
    // z unless another axis is charged less: a part without twist keeps its lines along z.
    int best = 2;
    for (const int k : {0, 1})
        if (charge[k] < charge[best]) best = k;
    return VolumeAxis(best);
}

double volume(const Scene& scene, int resolution, int threads, VolumeAxis axis) {
    const Bounds3 box = scene.bounds();
    if (box.empty()) return 0.0;
    if (!box.finite()) return kInfinity;
    // Lines along axis c, across the cells of the (a, b) plane, a right-handed cycle.
    const int c = int(axis == VolumeAxis::Auto ? volumeLineAxis(scene) : axis);
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    const Vec3 size = box.extent();
    const double cellA = size[a] / resolution, cellB = size[b] / resolution;
    // Rows on every worker, each summed on its own (to keep the running total's rounding
    // small), then added in row order: the same sum for any thread count.
    const int workers = resolveThreads(threads);
    std::vector<WorkerSlot<QueryContext>> contexts(static_cast<size_t>(workers));
    std::vector<double> rows(static_cast<size_t>(std::max(resolution, 0)), 0.0);
    parallelFor(rows.size(), workers, [&](int worker, uint64_t j) {
        QueryContext& ctx = contexts[size_t(worker)].value;
        double row = 0.0;
        for (int i = 0; i < resolution; ++i) {
            // Start before the box so every span is entered from outside; d is the unit axis.
            Ray ray;
            ray.o[a] = box.lo[a] + (i + 0.5) * cellA;
            ray.o[b] = box.lo[b] + (double(j) + 0.5) * cellB;
            ray.o[c] = box.lo[c] - 1.0;
            ray.d = Vec3(0.0);
            ray.d[c] = 1.0;
            for (const Span& s : scene.spans(ray, ctx)) row += s.out.t - s.in.t;
        }
        rows[j] = row;
    });
    double total = 0.0;
    for (const double row : rows) total += row;
    return total * cellA * cellB;
}

}  // namespace csg
