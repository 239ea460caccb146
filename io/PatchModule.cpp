#include "io/PatchModule.h"

#include <cmath>
#include <string_view>

#include "primitives/PatchSet.h"
#include "primitives/patch/Intersect.h"

namespace io {

namespace {

constexpr const char* kPatchForm =
    "bezier_patch(points = [16 points [x, y, z]], method = \"clip\", solid = false)";
constexpr const char* kPatchesForm =
    "bezier_patches(points = [[x, y, z], ...], patches = [[16 indices], ...], method = "
    "\"clip\", solid = false)";

// The arguments by name or position (names in order), each with its location.
struct Args {
    const InstantiationStmt& call;
    const char* form;
    std::vector<std::string_view> names;
    std::vector<Value> values;
    std::vector<Loc> locs;

    [[noreturn]] void bad(Evaluator& e, size_t i, const std::string& what) const {
        e.fail(locs[i], call.name + "(): '" + std::string(names[i]) + "' must be " + what +
                            ", got " + values[i].brief() + "; expected " + form);
    }
};

Args bindArgs(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx, const char* form,
              std::vector<std::string_view> names) {
    Args b{s, form, names, std::vector<Value>(names.size()), std::vector<Loc>(names.size(), s.loc)};
    size_t positional = 0;
    for (const ArgValue& a : e.evalArgs(s.args, ctx)) {
        size_t k = 0;
        if (a.name.empty()) {
            k = positional++;
            if (k >= names.size())
                e.fail(a.loc, "too many arguments to " + s.name + "(); expected " + form);
        } else {
            if (a.name[0] == '$') continue;  // $fn and friends: patches are exact
            while (k < names.size() && names[k] != a.name) ++k;
            if (k == names.size()) {
                e.warn(a.loc,
                       "unknown parameter '" + a.name + "' of " + s.name + "(); expected " + form);
                continue;
            }
        }
        b.values[k] = a.value;
        b.locs[k] = a.loc;
    }
    return b;
}

// A list of 3-D points: exactly `count` of them when count > 0, else at least one.
std::vector<csg::Vec3> pointsArg(Evaluator& e, const Args& b, size_t i, size_t count) {
    const std::string what = count > 0 ? "a list of " + std::to_string(count) + " points [x, y, z]"
                                       : "a non-empty list of points [x, y, z]";
    if (b.values[i].isUndef())
        e.fail(b.call.loc,
               b.call.name + "() needs '" + std::string(b.names[i]) + "'; expected " + b.form);
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

csg::PatchMethod methodArg(Evaluator& e, const Args& b, size_t i) {
    if (b.values[i].isUndef()) return csg::PatchMethod::Clip;
    std::string names;
    for (csg::PatchMethod m : csg::kAllPatchMethods)
        names += std::string(names.empty() ? "\"" : ", \"") + csg::patchMethodName(m) + "\"";
    std::optional<csg::PatchMethod> m;
    if (b.values[i].isString()) m = csg::patchMethodFromName(b.values[i].string());
    if (!m)
        e.fail(b.locs[i], b.call.name + "(): unknown method " + b.values[i].brief() +
                              "; expected one of " + names);
    return *m;
}

bool solidArg(Evaluator& e, const Args& b, size_t i) {
    if (b.values[i].isUndef()) return false;
    if (!b.values[i].isBool()) b.bad(e, i, "true or false");
    return b.values[i].asBool();
}

Instance finish(Evaluator& e, const InstantiationStmt& s, const GeomState& state, const Args& b,
                std::vector<csg::BezierPatch> patches, csg::PatchMethod method, bool solid) {
    if (!s.children.empty()) e.warn(s.loc, s.name + "() takes no children; they are ignored");
    const csg::PatchSet set = csg::PatchSet::make(std::move(patches), method, solid);
    if (const char* why = set.invalidReason())
        e.fail(s.loc, s.name + "(): " + why + "; expected " + b.form);
    return csg::leaf(set, {e.sourceTag(s.loc, e.childPath(state, s.name)), state.material});
}

}  // namespace

Instance bezierPatchModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                           const GeomState& state) {
    const Args b = bindArgs(e, s, ctx, kPatchForm, {"points", "method", "solid"});
    const std::vector<csg::Vec3> points = pointsArg(e, b, 0, 16);
    csg::BezierPatch patch;
    for (int k = 0; k < 16; ++k) patch.points[k] = points[k];
    return finish(e, s, state, b, {patch}, methodArg(e, b, 1), solidArg(e, b, 2));
}

Instance bezierPatchesModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                             const GeomState& state) {
    const Args b = bindArgs(e, s, ctx, kPatchesForm, {"points", "patches", "method", "solid"});
    const std::vector<csg::Vec3> points = pointsArg(e, b, 0, 0);
    // patches: lists of 16 whole indices into points.
    if (b.values[1].isUndef()) e.fail(s.loc, s.name + "() needs 'patches'; expected " + b.form);
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
    return finish(e, s, state, b, std::move(patches), methodArg(e, b, 2), solidArg(e, b, 3));
}

}  // namespace io
