// A set of bicubic Bezier patches: bezier_patch() and bezier_patches() in the language.
//
// Two kinds, by `solid`:
//   solid = false (the default): a SURFACE (a sheet). It has no inside; spans() lists each
//     crossing of the line as a zero-length span [t, t] (LocalSpans::sheet is set), which csg/
//     keeps instead of dropping as a sliver. Only a top-level object may be a sheet (compile
//     rejects one under difference or intersection).
//   solid = true: a closed, watertight, consistently oriented set. Its spans pair the sorted
//     crossings of all patches; crossings of patches that share an edge or a pole are one
//     crossing (tol::kPatchDedupeRel). An odd count after that is a numerical miss (a lost
//     grazing crossing or a duplicate the rule did not merge): the crossing closest to its
//     nearest neighbour is dropped (the first such in t on a tie), so the answer is
//     deterministic and never inverts inside and outside beyond that pair.
// Faces: the patch index (0 ..). Bounds: the union of the control-point boxes; each patch's
// own box is tested before the patch is solved.
#pragma once

#include <memory>
#include <vector>

#include "primitives/Primitive.h"
#include "primitives/patch/BezierPatch.h"

namespace csg {

struct PatchSetData;

struct PatchSet {
    // bezier_patch() makes a set of one patch.
    static constexpr const char* kName = "bezier_patches";

    std::shared_ptr<const PatchSetData> data;  // shared, immutable
    PatchMethod method = PatchMethod::Clip;
    bool solid = false;

    // Builds the set (never throws; bad input shows in invalidReason()).
    static PatchSet make(std::vector<BezierPatch> patches, PatchMethod method, bool solid);

    const char* invalidReason() const;
    bool isSheet() const { return !solid; }
    Bounds3 bounds() const;
    // Sheet: up to LocalSpans::kCapacity zero-length spans, nearest first. Solid: the pairs.
    void spans(const Vec3& o, const Vec3& d, LocalSpans& out) const;
    // Solid: parity of the crossings of a fixed ray from p. Sheet: false (no volume).
    bool inside(const Vec3& p) const;
    // Unit dS/du x dS/dv at the (u, v) of p on patch `face` (oriented outward for a solid; a
    // sheet's side is chosen by the scene, toward the ray's origin). Where the partials are
    // collinear or zero (a pole), the limit from inside the patch; never NaN.
    Vec3 normal(const Vec3& p, uint16_t face) const;
    // The number of patches, the method and whether the set is solid.
    void describe(JsonWriter& json) const;

    // One crossing of the whole set, for tests.
    struct Crossing {
        double t, u, v;
        uint32_t patch;
    };
    static constexpr int kMaxCrossings = 64;
    // Every crossing of the line o + t d, ascending, deduplicated; at most kMaxCrossings.
    int crossings(const Vec3& o, const Vec3& d, Crossing* out) const;
    // The (u, v) of the point of patch `face` nearest p: from the crossing at p when the last
    // spans() call on this thread found one there, else by searching the patch (see
    // PatchSet.cpp).
    Vec2 parameterOf(const Vec3& p, uint16_t face) const;
};

struct PatchSetData {
    std::vector<BezierPatch> patches;
    std::vector<Bounds3> hulls;  // per patch, tested before it is solved
    Bounds3 box;
    double size = 0.0;         // box diagonal: the dedupe rule's scale
    double volume = 0.0;       // signed volume the patches enclose (solid sets)
    double orientation = 1.0;  // -1 when the patches face inward: normals are negated
    const char* invalid = nullptr;
};

}  // namespace csg
