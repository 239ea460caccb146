#include "io/FacetedPrimitives.h"

#include <cmath>
#include <string>

namespace io {

namespace {

// Evaluation steps charged per vertex and per face of a faceted solid (see
// EvaluateOptions::maxSteps, ~5 bytes a step): a face keeps a 32-byte plane and a vertex 24
// bytes, and building them takes about as much again in face lists, so that a part of many
// finely faceted solids runs out of budget, not out of memory.
constexpr uint64_t kFacetSteps = 8;

// Why the solid has n fragments, for the too-many-faces message.
std::string countReason(const FragmentSettings& settings, int64_t n) {
    const std::string count = std::to_string(n) + " fragments";
    if (fnDecidesCount(settings)) return "$fn = " + formatNumber(settings.fn) + " gives " + count;
    return "$fa = " + formatNumber(settings.fa) + " and $fs = " + formatNumber(settings.fs) +
           " give " + count;
}

// The most fragments a solid whose face count grows with them may have (n >= 3).
template <class FaceCount>
int64_t mostFragments(FaceCount faceCount) {
    int64_t n = 3;
    while (faceCount(n + 1) <= csg::ConvexPolytope::kMaxPlanes) ++n;
    return n;
}

// The error for a face count over the limit, at the call, and the work charged for the solid,
// both before anything is built. mostFragmentsAllowed() names the limit in the message; it is asked
// only on that error.
template <class MostFragments>
void checkAndCharge(Evaluator& e, const InstantiationStmt& s, const FragmentSettings& settings,
                    int64_t n, uint64_t faces, MostFragments mostFragmentsAllowed) {
    if (faces > csg::ConvexPolytope::kMaxPlanes) {
        const int64_t most = mostFragmentsAllowed();
        e.fail(s.loc, s.name + "(): " + countReason(settings, n) + ", which make " +
                          std::to_string(faces) + " faces; a faceted " + s.name +
                          " may have at most " + std::to_string(csg::ConvexPolytope::kMaxPlanes) +
                          " (" + std::to_string(most) + " fragments); expected " +
                          (fnDecidesCount(settings) ? "a smaller $fn" : "a larger $fa or $fs") +
                          ", or --curves exact for the exact " + s.name);
    }
    // About as many vertices as faces (2 n + 2 against n + 2 for a cylinder).
    e.spend(s.loc, kFacetSteps * 2 * faces);
}

}  // namespace

csg::ConvexPolytope polytopeOf(FacetedSolid solid, csg::ConvexPolytope::Origin origin) {
    return csg::ConvexPolytope::fromFaces(std::move(solid.vertices), solid.faceVertices,
                                          solid.faceStarts, origin);
}

FragmentSettings unclampedFragmentSettings(Evaluator& e, const BoundArgs& b,
                                           const ContextPtr& ctx) {
    auto read = [&](const char* name) {
        const Value* given = nullptr;
        for (const ArgValue& a : b.all)
            if (a.name == name) given = &a.value;
        const Value value = given ? *given : e.lookupVariable(name, ctx, b.call.loc);
        return value.isNumber() ? value.number() : 0.0;
    };
    return FragmentSettings{read("$fn"), read("$fa"), read("$fs")};
}

FragmentSettings fragmentSettings(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx) {
    FragmentSettings settings = unclampedFragmentSettings(e, b, ctx);
    // OpenSCAD's order: $fs, then $fa.
    for (auto [name, value] : {std::pair{"$fs", &settings.fs}, std::pair{"$fa", &settings.fa}}) {
        if (!(*value < kMinFragmentSetting)) continue;
        e.warn(b.call.loc, std::string(name) + " = " + formatNumber(*value) +
                               " is too small; clamped to " + formatNumber(kMinFragmentSetting) +
                               ", as OpenSCAD does");
        *value = kMinFragmentSetting;
    }
    return settings;
}

std::optional<csg::ConvexPolytope> cylinderPolytope(Evaluator& e, const InstantiationStmt& s,
                                                    const FragmentSettings& settings, double h,
                                                    double r1, double r2, bool center) {
    if (!isFaceted(e.solidCurveMode(), settings)) return std::nullopt;
    const int64_t n = fragments(std::fmax(r1, r2), settings);
    const int64_t caps = (r1 > 0.0 ? 1 : 0) + (r2 > 0.0 ? 1 : 0);
    checkAndCharge(e, s, settings, n, facetedCylinderFaceCount(n, r1, r2),
                   [&] { return int64_t(csg::ConvexPolytope::kMaxPlanes) - caps; });
    // OpenSCAD's ends: z1 = 0 and z2 = h, or -h/2 and +h/2 centred.
    const double z1 = center ? -h / 2 : 0.0, z2 = center ? +h / 2 : h;
    return polytopeOf(facetedCylinder(r1, r2, z1, z2, n), {"cylinder", uint32_t(n), 0});
}

std::optional<csg::ConvexPolytope> spherePolytope(Evaluator& e, const InstantiationStmt& s,
                                                  const FragmentSettings& settings, double r) {
    if (!isFaceted(e.solidCurveMode(), settings)) return std::nullopt;
    const int64_t n = fragments(r, settings);
    checkAndCharge(e, s, settings, n, facetedSphereFaceCount(n),
                   [] { return mostFragments(facetedSphereFaceCount); });
    return polytopeOf(facetedSphere(r, n), {"sphere", uint32_t(n), uint32_t(sphereRingCount(n))});
}

}  // namespace io
