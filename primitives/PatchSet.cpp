// Notation: the set's line is o + t d in its local frame; a crossing is (t, patch, u, v).
// Finding (u, v) again at shading time: the hit stores only (t, face = patch), so normal()
// first looks for the crossing among those of the last spans() call on its thread (the
// renderer shades the closest hit of the ray it has just cast; probe asks about every span end
// of the ray it has just probed): a crossing on that patch at p gives (u, v) as the
// intersection found it. Otherwise (another ray's crossings, another instance of the set) it
// solves the closest-point problem on that patch: the nearest node of an 8 x 8 (u, v) grid.
// Both then run Gauss-Newton on |S(u, v) - p|^2. p lies on the patch up to rounding, so the
// residual at the answer is zero and Gauss-Newton converges quadratically (it is Newton
// there); the grid picks the right fold of a patch that comes back near itself (the teapot's
// handle). The search costs ~70 patch evaluations. Carrying (u, v) this way keeps Hit small
// for every ray; its cost is that every spans() call that finds crossings copies the line and
// each crossing's (t, u, v, patch) into a thread_local array (no allocation, no point formed:
// parameterOf forms one only for the shaded face's entries). A call that finds none, and
// inside(), leave the last copy as it was.
#include "primitives/PatchSet.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/Tolerances.h"
#include "primitives/patch/Intersect.h"
#include "primitives/solvers/LinePoint.h"

namespace csg {

namespace {

// 5-point Gauss-Legendre on [0, 1]: exact for degree 9, and S . (Su x Sv) has degree 8 in
// each of u and v, so the enclosed volume is exact up to rounding.
constexpr double kGaussNodes[5] = {0.04691007703066800, 0.23076534494715845, 0.5,
                                   0.76923465505284155, 0.95308992296933200};
constexpr double kGaussWeights[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                     0.23931433524968324, 0.11846344252809454};

// The direction inside() casts along: no symmetry of a test part lines up with it, so a ray
// along it rarely runs through edges or lies in a face.
const Vec3 kInsideDirection = glm::normalize(Vec3(0.5711, 0.6289, 0.5277));

// The crossings of the last spans() call on this thread that found any: the line and each
// crossing's t. The local point is formed only when normal() asks (parameterOf), so the
// calls whose crossings are never shaded (shadow rays, objects behind the hit) do not pay.
struct LastCrossings {
    const PatchSetData* set = nullptr;
    Vec3 o, d;
    int count = 0;
    struct Entry {
        double t;
        Vec2 uv;
        uint32_t patch;
    } entries[PatchSet::kMaxCrossings];
};
thread_local LastCrossings lastCrossings;

// Gauss-Newton on |S(u, v) - p|^2 from start, clamped to the unit square.
Vec2 closestParameterFrom(const BezierPatch& patch, const Vec3& p, Vec2 uv) {
    for (int step = 0; step < 30; ++step) {
        const Vec3 r = p - patch.eval(uv.x, uv.y);
        const Vec3 su = patch.du(uv.x, uv.y), sv = patch.dv(uv.x, uv.y);
        const double a = glm::dot(su, su), b = glm::dot(su, sv), e = glm::dot(sv, sv);
        const double det = a * e - b * b;
        if (!(det > 0.0) || !std::isfinite(det)) break;  // a pole: the start stands
        const double gu = glm::dot(su, r), gv = glm::dot(sv, r);
        const Vec2 step2((e * gu - b * gv) / det, (a * gv - b * gu) / det);
        const Vec2 next = glm::clamp(uv + step2, Vec2(0.0), Vec2(1.0));
        const Vec2 moved = next - uv;
        uv = next;
        if (std::max(std::abs(moved.x), std::abs(moved.y)) < tol::kPatchNewtonStep) break;
    }
    return uv;
}

double signedVolume(const std::vector<BezierPatch>& patches) {
    double v = 0.0;
    for (const BezierPatch& p : patches)
        for (int a = 0; a < 5; ++a)
            for (int b = 0; b < 5; ++b) {
                const double u = kGaussNodes[a], w = kGaussNodes[b];
                v += kGaussWeights[a] * kGaussWeights[b] *
                     glm::dot(p.eval(u, w), glm::cross(p.du(u, w), p.dv(u, w)));
            }
    return v / 3.0;
}

}  // namespace

PatchSet PatchSet::make(std::vector<BezierPatch> patches, PatchMethod method, bool solid) {
    auto data = std::make_shared<PatchSetData>();
    data->patches = std::move(patches);
    PatchSet set{nullptr, method, solid};
    for (const BezierPatch& p : data->patches)
        for (const Vec3& q : p.points)
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                data->invalid = "bezier patch control points must be finite";
    if (data->patches.empty()) data->invalid = "a patch set needs at least one patch";
    if (data->patches.size() > 65535) data->invalid = "a patch set holds at most 65535 patches";
    if (!data->invalid) {
        for (const BezierPatch& p : data->patches) {
            data->hulls.push_back(p.hullBounds());
            data->box.extend(data->hulls.back());
        }
        data->size = glm::length(data->box.extent());
        if (!(data->size > 0.0)) data->invalid = "the patches are a single point";
    }
    if (!data->invalid && solid) {
        data->volume = signedVolume(data->patches);
        if (data->volume < 0.0) data->orientation = -1.0;
        // A closed set encloses a volume; an open one still gives some number, so this only
        // catches sets with nothing inside (a flat or doubled-up set).
        const double s = data->size;
        if (!(std::abs(data->volume) > tol::kSingularDetRel * s * s * s) ||
            !std::isfinite(data->volume))
            data->invalid =
                "solid=true but the patches enclose no volume (a solid set must be "
                "closed and consistently oriented)";
    }
    set.data = data;
    return set;
}

const char* PatchSet::invalidReason() const {
    return data ? data->invalid : "patch set was not built";
}

void PatchSet::describe(JsonWriter& json) const {
    json.key("patches").value(uint64_t(data ? data->patches.size() : 0));
    json.key("method").value(patchMethodName(method));
    json.key("solid").value(solid);
}

Bounds3 PatchSet::bounds() const {
    return data && !data->invalid ? data->box : Bounds3{Vec3(0.0), Vec3(0.0)};
}

int PatchSet::crossings(const Vec3& o, const Vec3& d, Crossing* out) const {
    if (!data || data->invalid) return 0;
    const SlabRay slab(o, d);
    int n = 0;
    for (size_t i = 0; i < data->patches.size(); ++i) {
        // Step 1: the patch's own box, and the line restarted at its entry.
        double t0 = -kInfinity, t1 = kInfinity;
        if (!clipToBox(slab, data->hulls[i], t0, t1)) continue;
        const double shift = std::isfinite(t0) ? t0 : 0.0;
        PatchCrossings found;
        const int m = intersectPatch(method, data->patches[i], pointOnLine(o, d, shift), d, found);
        // Step 2: collect (the far ones fall off when a line crosses more than we hold).
        for (int k = 0; k < m && n < kMaxCrossings; ++k)
            out[n++] = {found[k].t + shift, found[k].u, found[k].v, static_cast<uint32_t>(i)};
    }
    // Step 3: ascending; a crossing on an edge or pole shared by patches is listed once.
    std::sort(out, out + n, [](const Crossing& a, const Crossing& b) {
        return a.t < b.t || (a.t == b.t && a.patch < b.patch);
    });
    const double gap = tol::kPatchDedupeRel * data->size / glm::length(d);
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (m == 0 || out[i].t - out[m - 1].t > gap) out[m++] = out[i];
    return m;
}

void PatchSet::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    Crossing c[kMaxCrossings];
    int n = crossings(o, d, c);
    if (n > 0) {
        lastCrossings.set = data.get();
        lastCrossings.o = o, lastCrossings.d = d;
        lastCrossings.count = n;
        for (int i = 0; i < n; ++i)
            lastCrossings.entries[i] = {c[i].t, Vec2(c[i].u, c[i].v), c[i].patch};
    }
    auto face = [&](int i) { return static_cast<uint16_t>(c[i].patch); };
    if (!solid) {
        out.sheet = true;
        for (int i = 0; i < n && out.count < LocalSpans::kCapacity; ++i)
            out.add(c[i].t, face(i), c[i].t, face(i));
        return;
    }
    // An odd count: drop the crossing nearest its neighbour (see PatchSet.h).
    if (n % 2 == 1) {
        int drop = 0;
        double best = kInfinity;
        for (int i = 0; i < n; ++i) {
            const double gapPrev = i > 0 ? c[i].t - c[i - 1].t : kInfinity;
            const double gapNext = i + 1 < n ? c[i + 1].t - c[i].t : kInfinity;
            if (std::min(gapPrev, gapNext) < best) best = std::min(gapPrev, gapNext), drop = i;
        }
        std::copy(c + drop + 1, c + n, c + drop);
        --n;
    }
    for (int i = 0; i + 1 < n && out.count < LocalSpans::kCapacity; i += 2)
        out.add(c[i].t, face(i), c[i + 1].t, face(i + 1));
}

bool PatchSet::inside(const Vec3& p) const {
    if (!solid || !data || data->invalid || !data->box.contains(p)) return false;
    Crossing c[kMaxCrossings];
    const int n = crossings(p, kInsideDirection, c);
    int ahead = 0;
    for (int i = 0; i < n; ++i) ahead += c[i].t > 0.0;
    return ahead % 2 == 1;
}

Vec2 PatchSet::parameterOf(const Vec3& p, uint16_t face) const {
    const BezierPatch& patch = data->patches[face];
    // Step 1: a crossing of the last spans() call on this patch at p already knows (u, v).
    if (lastCrossings.set == data.get()) {
        const double near = tol::kPatchCarriedPointRel * data->size;
        for (int i = 0; i < lastCrossings.count; ++i) {
            const LastCrossings::Entry& e = lastCrossings.entries[i];
            if (e.patch != face) continue;
            const Vec3 gap = pointOnLine(lastCrossings.o, lastCrossings.d, e.t) - p;
            if (glm::dot(gap, gap) <= near * near) return closestParameterFrom(patch, p, e.uv);
        }
    }
    // Step 2: else the nearest node of a coarse grid.
    constexpr int kGrid = 8;
    Vec2 best(0.5);
    double bestDistance = kInfinity;
    for (int a = 0; a < kGrid; ++a)
        for (int b = 0; b < kGrid; ++b) {
            const Vec2 uv((a + 0.5) / kGrid, (b + 0.5) / kGrid);
            const Vec3 q = patch.eval(uv.x, uv.y) - p;
            const double dist = glm::dot(q, q);
            if (dist < bestDistance) bestDistance = dist, best = uv;
        }
    // Step 3: Gauss-Newton from there.
    return closestParameterFrom(patch, p, best);
}

Vec3 PatchSet::normal(const Vec3& p, uint16_t face) const {
    if (!data || data->invalid || face >= data->patches.size()) return Vec3(0.0, 0.0, 1.0);
    const BezierPatch& patch = data->patches[face];
    const Vec2 uv = parameterOf(p, face);
    // Step 1: dS/du x dS/dv; where it degenerates (collinear partials, or a partial that is
    // only rounding noise at a pole or a cusp), the limit along the way into the patch's
    // centre, at growing distances.
    const double size = glm::length(data->hulls[face].extent());
    for (double step : {0.0, 1e-7, 1e-5, 1e-3, 1e-1}) {
        const Vec2 q = uv + step * (Vec2(0.5) - uv);
        const Vec3 su = patch.du(q.x, q.y), sv = patch.dv(q.x, q.y);
        const Vec3 n = glm::cross(su, sv);
        const double len = glm::length(n);
        const double scale = std::max(glm::length(su) * glm::length(sv), size * size);
        if (len > tol::kPatchNormalDegenerateRel * scale && std::isfinite(len))
            return data->orientation * n / len;
    }
    // Step 2: a patch degenerate everywhere near p: the plane of its corner diagonals, else +z.
    const Vec3 n = glm::cross(patch.at(3, 3) - patch.at(0, 0), patch.at(3, 0) - patch.at(0, 3));
    const double len = glm::length(n);
    return len > 0.0 && std::isfinite(len) ? data->orientation * n / len : Vec3(0.0, 0.0, 1.0);
}

}  // namespace csg
