#include "io/PatchModule.h"

#include <cmath>
#include <string_view>

#include "io/BoundArgs.h"
#include "primitives/PatchSet.h"
#include "primitives/patch/Intersect.h"

namespace io {

namespace {

constexpr const char* kPatchForm =
    "bezier_patch(points = [16 points [x, y, z]], method = \"clip\", solid = false)";
constexpr const char* kPatchesForm =
    "bezier_patches(points = [[x, y, z], ...], patches = [[16 indices], ...], method = "
    "\"clip\", solid = false)";

// A list of 3-D points: exactly `count` of them when count > 0, else at least one.
std::vector<csg::Vec3> pointsArg(Evaluator& e, const BoundArgs& b, size_t i, size_t count) {
    const std::string what = count > 0 ? "a list of " + std::to_string(count) + " points [x, y, z]"
                                       : "a non-empty list of points [x, y, z]";
    if (b.values[i].isUndef())
        e.fail(b.call.loc, b.call.name + "() needs '" + std::string(b.names[i]) + "'; expected " +
                               std::string(b.form));
    const Value& v = b.values[i];
    if (!v.isVector() || v.list().empty() || (count > 0 && v.list().size() != count))
        b.bad(e, i, what);
    std::vector<csg::Vec3> points;
    for (size_t p = 0; p < v.list().size(); ++p) {
        const Value& q = v.list()[p];
        if (!q.isVector() || q.list().size() != 3)
            b.bad(e, i, what + " (entry " + std::to_string(p) + " is not [x, y, z])");
        csg::Vec3 point;
        for (int k = 0; k < 3; ++k) {
            const Value& x = q.list()[k];
            if (!x.isNumber() || !std::isfinite(x.number()))
                b.bad(e, i, what + " of finite numbers (entry " + std::to_string(p) + " is not)");
            point[k] = x.number();
        }
        points.push_back(point);
    }
    return points;
}

csg::PatchMethod patchMethodArg(Evaluator& e, const BoundArgs& b, size_t i) {
    return choiceArg(e, b, i, "method", csg::kAllPatchMethods, csg::patchMethodName,
                     csg::PatchMethod::Clip);
}

bool solidArg(Evaluator& e, const BoundArgs& b, size_t i) {
    if (b.values[i].isUndef()) return false;
    if (!b.values[i].isBool()) b.bad(e, i, "true or false");
    return b.values[i].asBool();
}

Instance finish(Evaluator& e, const InstantiationStmt& s, const GeomState& state,
                const BoundArgs& b, std::vector<csg::BezierPatch> patches, csg::PatchMethod method,
                bool solid) {
    const csg::PatchSet set = csg::PatchSet::make(std::move(patches), method, solid);
    if (const char* why = set.invalidReason())
        e.fail(s.loc, s.name + "(): " + why + "; expected " + std::string(b.form));
    return csg::leaf(set, {e.sourceTag(s.loc, e.childPath(state, s.name)), state.material});
}

}  // namespace

Instance bezierPatchModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                           const GeomState& state) {
    const BoundArgs b = bindArgs(e, s, ctx, {"points", "method", "solid"}, kPatchForm);
    const std::vector<csg::Vec3> points = pointsArg(e, b, 0, 16);
    csg::BezierPatch patch;
    for (int k = 0; k < 16; ++k) patch.points[k] = points[k];
    return finish(e, s, state, b, {patch}, patchMethodArg(e, b, 1), solidArg(e, b, 2));
}

Instance bezierPatchesModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state) {
    const BoundArgs b = bindArgs(e, s, ctx, {"points", "patches", "method", "solid"}, kPatchesForm);
    const std::vector<csg::Vec3> points = pointsArg(e, b, 0, 0);
    // patches: lists of 16 whole indices into points.
    if (b.values[1].isUndef())
        e.fail(s.loc, s.name + "() needs 'patches'; expected " + std::string(b.form));
    const Value& v = b.values[1];
    if (!v.isVector() || v.list().empty()) b.bad(e, 1, "a non-empty list of patches");
    std::vector<csg::BezierPatch> patches;
    for (size_t p = 0; p < v.list().size(); ++p) {
        const Value& row = v.list()[p];
        const std::string which = "patch " + std::to_string(p);
        if (!row.isVector() || row.list().size() != 16)
            b.bad(e, 1,
                  "lists of 16 indices (" + which + " has " +
                      (row.isVector() ? std::to_string(row.list().size()) : "none") + ")");
        csg::BezierPatch patch;
        for (size_t k = 0; k < 16; ++k) {
            const Value& x = row.list()[k];
            const double index = x.isNumber() ? x.number() : -1.0;
            if (!x.isNumber() || !(index >= 0 && index < double(points.size())) ||
                index != std::floor(index))
                b.bad(e, 1,
                      "lists of whole indices in [0, " + std::to_string(points.size() - 1) + "] (" +
                          which + ", entry " + std::to_string(k) + " is " + x.brief() + ")");
            patch.points[k] = points[static_cast<size_t>(index)];
        }
        patches.push_back(patch);
    }
    return finish(e, s, state, b, std::move(patches), patchMethodArg(e, b, 2), solidArg(e, b, 3));
}

}  // namespace io
