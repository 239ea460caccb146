#include "csg/mesh/MeshDistance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "primitives/base/ParallelFor.h"
#include "primitives/base/Tolerances.h"

namespace csg {

namespace {

// Running figures of one worker, merged at the end.
struct Accumulator {
    DistanceStats stats;
    double sum = 0.0;
    void add(const Vec3& p, double d) {
        ++stats.samples;
        if (!std::isfinite(d))
            ++stats.unresolved;
        else
            sum += d;
        if (d > stats.max || stats.samples == 1) {
            stats.max = d;
            stats.worst = p;
        }
    }
};

DistanceStats merge(const std::vector<Accumulator>& parts) {
    DistanceStats out;
    double sum = 0.0;
    bool first = true;
    for (const Accumulator& a : parts) {
        if (a.stats.samples == 0) continue;
        out.samples += a.stats.samples;
        out.unresolved += a.stats.unresolved;
        sum += a.sum;
        if (first || a.stats.max > out.max) {
            out.max = a.stats.max;
            out.worst = a.stats.worst;
            first = false;
        }
    }
    const uint64_t resolved = out.samples - out.unresolved;
    out.mean = resolved ? sum / double(resolved) : 0.0;
    return out;
}

// What a line through a sample found: the smallest |t| of a surface span end of the scene along
// p + t d, t in [-reach, reach], and the part's outward normal there (zero when nothing).
struct LineHit {
    double distance = kInfinity;
    Vec3 normal{0.0};
};

LineHit nearestAlongLine(const Scene& scene, QueryContext& ctx, const Vec3& p, const Vec3& d,
                         double reach) {
    const Ray ray{p, d, -reach, reach};
    LineHit best;
    Hit nearest;
    const auto consider = [&](const Hit& h) {
        if (h.isSurface() && std::fabs(h.t) < best.distance) {
            best.distance = std::fabs(h.t);
            nearest = h;
        }
    };
    for (const Span& s : scene.spans(ray, ctx)) {
        consider(s.in);
        consider(s.out);
    }
    if (std::isfinite(best.distance)) best.normal = scene.surface(ray, nearest).normal;
    return best;
}

// kFanLines unit directions on a golden-angle spiral over the upper half of the sphere
// (z from 1 down to 0): read as two-sided lines they cover all directions, the angle between
// neighbours about 180 / sqrt(kFanLines) degrees.
constexpr int kFanLines = 64;
const std::array<Vec3, kFanLines>& fanDirections() {
    static const std::array<Vec3, kFanLines> fan = [] {
        std::array<Vec3, kFanLines> d{};
        const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
        for (int i = 0; i < kFanLines; ++i) {
            const double z = 1.0 - (double(i) + 0.5) / kFanLines;
            const double r = std::sqrt(1.0 - z * z);
            d[size_t(i)] = Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z);
        }
        return d;
    }();
    return fan;
}

// A sample's bound so far: the best line's answer, whether the fan has been tried, and whether
// foot steps from that answer have stopped gaining (another would measure the same line again).
struct SampleBound {
    LineHit best;
    bool fanned = false;
    bool settled = false;
    void keep(const LineHit& h, double added = 0.0) {
        if (h.distance + added < best.distance)
            best = {h.distance + added, h.normal}, settled = false;
    }
};

// Lines along the surface normal where the best line met the surface, each from the last
// one's hit: the best of a few lines can meet a smooth surface well off its normal and read a
// quarter above the distance (mesh_test: 0.1257 for 0.1), while the line along the normal where
// it met runs through the foot point of a surface that curves little between the two points.
template <class Measure>
void footSteps(SampleBound& bound, Measure&& measure) {
    if (bound.settled) return;
    for (int step = 0; step < tol::kDistanceFootSteps && bound.best.normal != Vec3(0.0); ++step) {
        const double before = bound.best.distance;
        bound.keep(measure(bound.best.normal, Vec3(0.0)));
        if (!(bound.best.distance < before)) {
            bound.settled = true;
            return;
        }
    }
}

// A bound tightened while it stays above `floor`: foot steps, then (where the nearest surface
// point is on an edge, which no normal line reaches) the fan and foot steps from its best line.
template <class Measure>
void tighten(SampleBound& bound, double floor, Measure&& measure) {
    footSteps(bound, measure);
    if (bound.fanned || !(bound.best.distance > floor)) return;
    for (const Vec3& d : fanDirections()) bound.keep(measure(d, Vec3(0.0)));
    bound.fanned = true;
    footSteps(bound, measure);
}

// The first direction, then the three axes and four body diagonals when the first answer is
// not well within goodEnough (tol::kDistanceFirstLineFraction: near a crease the first line can
// run almost along the surface and overestimate several times, and a loose bound just under
// goodEnough is still read as an error against it). The extra lines matter at creases: a point
// on a concave edge of axis-aligned faces has its normal and all three axis lines lying in the
// faces (regularized spans then put the nearest surface end far away), while a diagonal line
// crosses the boundary at the point.
template <class Measure>
SampleBound boundAlongLines(const Vec3& first, double goodEnough, Measure&& measure) {
    static const Vec3 kExtra[7] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 1},
                                   {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    SampleBound bound;
    const double len = glm::length(first);
    if (len > 0.0) bound.keep(measure(first / len, Vec3(0.0)));
    if (bound.best.distance > tol::kDistanceFirstLineFraction * goodEnough)
        for (const Vec3& d : kExtra) bound.keep(measure(glm::normalize(d), Vec3(0.0)));
    // A point on an edge where two solids only touch (a non-manifold part) sees every line
    // through it either miss both solids or cross both with fused spans, and a point on a
    // convex corner sees most lines only touch the solid there (a zero-length span, dropped):
    // measure again from a point a hair away in a direction of no symmetry, and add the hair;
    // where solids touch tangentially the gap opens only quadratically, so farther hairs follow.
    const Vec3 away = glm::normalize(Vec3(0.5377, 0.8117, 0.2283));
    for (double fraction = tol::kDistanceShiftFraction;
         bound.best.distance > goodEnough && fraction <= tol::kDistanceShiftMaxFraction;
         fraction *= 10.0) {
        const Vec3 shift = away * goodEnough * fraction;
        for (const Vec3& d : kExtra)
            bound.keep(measure(glm::normalize(d), shift), glm::length(shift));
    }
    // A point just off an edge of the part, beside a thin wedge of its material (a faceted
    // sphere's rim standing above the exact rim of a hole through it), can have the nearest
    // surface within goodEnough while all of those lines pass beside the wedge or graze it:
    // then the fan, for any answer the meshing would reject (its margin of goodEnough).
    if (bound.best.distance > tol::kMeshMeasureMargin * goodEnough) tighten(bound, 0.0, measure);
    return bound;
}

// Runs measure(worker, item, accumulator) over count items, on this process's workers or on the
// processes of a job (options.distribute), and merges what they found: one accumulator per item,
// merged in item order, so that the figures do not depend on which worker took which item (a
// chunk of meshToSurface tightens its samples against its accumulator's maximum so far, and the
// sum's rounding depends on its order: one accumulator per worker gave means that differed
// between runs on two threads, in the fifth digit on samples/knob.scad).
template <class Measure>
DistanceStats measureItems(uint64_t count, std::string_view what, int workers,
                           const DistanceOptions& options, Measure&& measure) {
    std::vector<Accumulator> acc(static_cast<size_t>(count));
    if (!options.distribute) {
        // Each item measured into an accumulator of its own stack, not into its neighbour's cache
        // line.
        parallelFor(count, workers, [&](int w, uint64_t item) {
            Accumulator found;
            measure(w, item, found);
            acc[size_t(item)] = found;
        });
        return merge(acc);
    }
    options.distribute->run(
        count, what,
        [&](int w, uint64_t item, std::string& bytes) {
            Accumulator found;
            measure(w, item, found);
            ByteWriter(bytes).value(found);
        },
        [&](uint64_t item, std::string_view bytes) {
            acc[size_t(item)] = ByteReader(bytes).value<Accumulator>();
        });
    return merge(acc);
}

}  // namespace

DistanceStats meshToSurface(const Scene& scene, const TriangleMesh& mesh,
                            const DistanceOptions& options) {
    const int workers = workersFor(options.distribute, options.threads);
    std::vector<QueryContext> ctx(static_cast<size_t>(workers));
    // Each vertex is sampled from the first triangle that has it.
    std::vector<uint32_t> owner(mesh.positions.size(), UINT32_MAX);
    for (uint32_t t = uint32_t(mesh.triangles.size()); t-- > 0;)
        for (const uint32_t v : mesh.triangles[t]) owner[v] = t;
    const uint64_t triangles = mesh.triangles.size();
    constexpr uint64_t kChunk = 1024;
    // A chunk's samples whose bounds are loose enough to matter, each tightened only while it
    // could still be the maximum: in falling order, until one's bound is at most the largest
    // figure already taken (and so is every bound after it).
    struct Candidate {
        Vec3 point;
        SampleBound bound;
    };
    std::vector<std::vector<Candidate>> candidates(static_cast<size_t>(workers));
    const auto chunkOf = [&](int w, uint64_t chunk, Accumulator& acc) {
        const auto measureFrom = [&](const Vec3& p) {
            return
                [&scene, &ctx = ctx[size_t(w)], p, &options](const Vec3& dir, const Vec3& shift) {
                    return nearestAlongLine(scene, ctx, p + shift, dir, options.reach);
                };
        };
        std::vector<Candidate>& loose = candidates[size_t(w)];
        loose.clear();
        // The mesh point p, measured first along the normal n of its triangle.
        auto measureAt = [&](const Vec3& p, const Vec3& n) {
            const SampleBound bound = boundAlongLines(n, options.goodEnough, measureFrom(p));
            if (bound.best.distance > tol::kDistanceFirstLineFraction * options.goodEnough &&
                std::isfinite(bound.best.distance))
                loose.push_back({p, bound});
            else
                acc.add(p, bound.best.distance);
        };
        for (uint64_t t = chunk * kChunk; t < std::min((chunk + 1) * kChunk, triangles); ++t) {
            const auto& tri = mesh.triangles[size_t(t)];
            const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]],
                       c = mesh.positions[tri[2]];
            const Vec3 n = glm::cross(b - a, c - a), centroid = (a + b + c) / 3.0;
            measureAt(centroid, n);
            // Corners and edge midpoints lie on the part's edges when the mesh follows them, where
            // a line may only graze the solid: they are sampled a hair inside the triangle (points
            // of the mesh as much as the corners are).
            const auto inset = [&](const Vec3& p) {
                return p + tol::kDistanceSampleInset * (centroid - p);
            };
            for (int k = 0; k < 3; ++k) {
                const uint32_t i = tri[size_t(k)], j = tri[size_t((k + 1) % 3)];
                const Vec3 p = mesh.positions[i], q = mesh.positions[j];
                if (owner[i] == t) measureAt(inset(p), n);
                // Each edge once: from the triangle that runs it from its lower index (a closed
                // oriented mesh runs every edge once each way).
                if (i < j) measureAt(inset(0.5 * (p + q)), n);
            }
        }
        std::sort(loose.begin(), loose.end(), [](const Candidate& x, const Candidate& y) {
            return x.bound.best.distance > y.bound.best.distance;
        });
        for (Candidate& c : loose) {
            const double floor = acc.stats.samples == 0 ? 0.0 : acc.stats.max;
            if (c.bound.best.distance > floor) tighten(c.bound, floor, measureFrom(c.point));
            acc.add(c.point, c.bound.best.distance);
        }
    };
    return measureItems((triangles + kChunk - 1) / kChunk, "the mesh measured to the surface",
                        workers, options, chunkOf);
}

DistanceStats surfaceToMesh(const Scene& scene, const TriangleBvh& bvh, int raysPerAxis,
                            const DistanceOptions& options) {
    const Bounds3 box = scene.bounds();
    if (box.empty() || !box.finite() || raysPerAxis <= 0) return {};
    const int workers = workersFor(options.distribute, options.threads);
    std::vector<QueryContext> ctx(static_cast<size_t>(workers));
    const Vec3 size = box.extent();
    // One work item per row of lines; rows of the three axes one after another.
    const auto rowOf = [&](int w, uint64_t item, Accumulator& acc) {
        const int a = int(item / uint64_t(raysPerAxis)), row = int(item % uint64_t(raysPerAxis));
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int col = 0; col < raysPerAxis; ++col) {
            // Step 1: a line through cell centres of the bounds' face, from outside the box.
            Ray ray;
            ray.o[a] = box.lo[a] - 1.0;
            ray.o[b] = box.lo[b] + (col + 0.5) * size[b] / raysPerAxis;
            ray.o[c] = box.lo[c] + (row + 0.5) * size[c] / raysPerAxis;
            ray.d = Vec3(0.0);
            ray.d[a] = 1.0;
            ray.tmin = 0.0;
            ray.tmax = size[a] + 2.0;
            // Step 2: each surface span end is an exact surface point. The span list lives in
            // ctx until the next query, so copy the few hits' parameters out first.
            double hits[64];
            int count = 0;
            for (const Span& s : scene.spans(ray, ctx[size_t(w)])) {
                if (count + 2 > 64) break;
                if (s.in.isSurface()) hits[count++] = s.in.t;
                if (s.out.isSurface()) hits[count++] = s.out.t;
            }
            // Step 3: the Euclidean distance to the mesh, exact up to rounding (the mesh is
            // explicit, unlike the surface: no line has to find it, and no normal is needed).
            for (int i = 0; i < count; ++i) {
                const Vec3 point = ray.at(hits[i]);
                acc.add(point, bvh.distance(point, options.reach));
            }
        }
    };
    return measureItems(uint64_t(3) * uint64_t(raysPerAxis), "the surface measured to the mesh",
                        workers, options, rowOf);
}

}  // namespace csg
