// The built-in modules: OpenSCAD's solids, booleans, transforms and color, csgray's scene
// modules (camera, light, background, material, halfspace), and a clear error for each
// OpenSCAD module csgray does not support yet.
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "io/BoundArgs.h"
#include "io/Colors.h"
#include "io/Degrees.h"
#include "io/DerivedModules.h"
#include "io/Evaluator.h"
#include "io/FacetedPrimitives.h"
#include "io/MeasureModules.h"
#include "io/MeshModules.h"
#include "io/Modules2D.h"
#include "io/PatchModule.h"
#include "io/Shapes2D.h"
#include "io/SurfaceModule.h"
#include "io/TextModule.h"
#include "primitives/base/Tolerances.h"
#include "viewer/render/PngReader.h"

namespace io {

namespace {

using csg::Mat4;
using csg::Vec3;

// A vector of 2 or 3 finite numbers (missing entries take `fill`), or with allowScalar a
// number for all three.
Vec3 vecArg(Evaluator& e, const BoundArgs& b, size_t i, Vec3 dflt, double fill, bool allowScalar,
            bool allow2 = true) {
    if (!b.given(i)) return dflt;
    const Value& v = b[i];
    if (allowScalar && v.isNumber() && std::isfinite(v.number())) return Vec3(v.number());
    const char* what = allowScalar ? (allow2 ? "a number or a vector of 2 or 3 numbers"
                                             : "a number or a vector of 3 numbers")
                                   : "a vector of 2 or 3 numbers";
    if (!v.isVector()) b.bad(e, i, what);
    const ValueList& l = v.list();
    if (l.size() != 3 && !(allow2 && l.size() == 2)) b.bad(e, i, what);
    Vec3 out(fill);
    for (size_t k = 0; k < l.size(); ++k) {
        if (!l[k].isNumber() || !std::isfinite(l[k].number())) b.bad(e, i, what);
        out[static_cast<int>(k)] = l[k].number();
    }
    return out;
}

// An RGBA color from a name, a hex string or a vector of 3 or 4 numbers.
std::optional<csg::Vec4> colorArg(Evaluator& e, const BoundArgs& b, size_t i) {
    if (!b.given(i)) return std::nullopt;
    const Value& v = b[i];
    if (v.isString()) {
        if (auto c = parseColor(v.string())) return c;
        e.warn(b.loc(i), "unknown color \"" + v.string() +
                             "\" (expected a CSS color name or "
                             "#rrggbb); color unchanged");
        return std::nullopt;
    }
    if (v.isVector() && (v.list().size() == 3 || v.list().size() == 4)) {
        csg::Vec4 c(1.0);
        for (size_t k = 0; k < v.list().size(); ++k) {
            if (!v.list()[k].isNumber()) b.bad(e, i, "a color");
            c[static_cast<int>(k)] = v.list()[k].number();
        }
        return c;
    }
    b.bad(e, i, "a color name, \"#rrggbb\" or [r, g, b] / [r, g, b, a]");
}

// A vector of up to 3 numbers as OpenSCAD's transforms read it (missing entries are `fill`), or
// nothing when the value is not one: OpenSCAD then warns and uses the identity.
std::optional<Vec3> transformVector(const Value& v, double fill, bool allowScalar) {
    if (allowScalar && v.isNumber() && std::isfinite(v.number())) return Vec3(v.number());
    if (!v.isVector() || v.list().size() < 2 || v.list().size() > 3) return std::nullopt;
    Vec3 out(fill);
    for (size_t k = 0; k < v.list().size(); ++k) {
        if (!v.list()[k].isNumber() || !std::isfinite(v.list()[k].number())) return std::nullopt;
        out[static_cast<int>(k)] = v.list()[k].number();
    }
    return out;
}

uint32_t leafTag(Evaluator& e, const InstantiationStmt& s, const GeomState& state) {
    return e.sourceTag(s.loc, e.childPath(state, s.name));
}

// ---- solids ----

Instance cube(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
              const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"size", "center"}, "cube(size, center)");
    fragmentSettings(e, b, ctx);  // only for OpenSCAD's warnings about $fa and $fs
    Vec3 size(1.0);
    if (b.given(0)) {
        const std::optional<Vec3> read = transformVector(b[0], 0.0, true);
        if (read && (b[0].isNumber() || b[0].list().size() == 3))
            size = *read;
        else  // OpenSCAD warns and builds the default unit cube
            e.warn(b.loc(0), "Unable to convert cube(size=" + b[0].brief() +
                                 ", ...) parameter to a number or a vec3 of numbers");
    }
    const bool center = boolArg(e, b, 1, false);
    if (size.x <= 0 || size.y <= 0 || size.z <= 0) {
        e.warn(s.loc, "cube() with a size that is not positive in every axis is empty");
        return csg::NodePtr();
    }
    const Vec3 lo = center ? -0.5 * size : Vec3(0.0);
    return csg::leaf(csg::Box{lo, lo + size}, {leafTag(e, s, state), state.material});
}

Instance sphere(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"r", "d"}, "sphere(r | d)");
    const FragmentSettings facets = fragmentSettings(e, b, ctx);
    double r = numberArg(e, b, 0, 1.0);
    if (b.given(1)) r = numberArg(e, b, 1, 2.0) / 2.0;  // d wins over r, as in OpenSCAD
    if (r <= 0) {
        e.warn(s.loc, "sphere() with a radius that is not positive is empty");
        return csg::NodePtr();
    }
    if (auto faceted = spherePolytope(e, s, facets, r))
        return csg::leaf(std::move(*faceted), {leafTag(e, s, state), state.material});
    return csg::leaf(csg::Sphere{r}, {leafTag(e, s, state), state.material});
}

Instance cylinder(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                  const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"h", "r1", "r2", "center", "r", "d", "d1", "d2"},
                           "cylinder(h, r|d, r1|d1, r2|d2, center)");
    const FragmentSettings facets = fragmentSettings(e, b, ctx);
    const double h = numberArg(e, b, 0, 1.0);
    // OpenSCAD's precedence: d over r, d1 over r1, d2 over r2; r1/r2 over r.
    double r1 = 1.0, r2 = 1.0;
    if (b.given(5))
        r1 = r2 = numberArg(e, b, 5, 2.0) / 2.0;
    else if (b.given(4))
        r1 = r2 = numberArg(e, b, 4, 1.0);
    if (b.given(6))
        r1 = numberArg(e, b, 6, 2.0) / 2.0;
    else if (b.given(1))
        r1 = numberArg(e, b, 1, 1.0);
    if (b.given(7))
        r2 = numberArg(e, b, 7, 2.0) / 2.0;
    else if (b.given(2))
        r2 = numberArg(e, b, 2, 1.0);
    const bool center = boolArg(e, b, 3, false);
    if (h <= 0 || r1 < 0 || r2 < 0 || (r1 == 0 && r2 == 0)) {
        e.warn(s.loc, "cylinder() with a height or radii that are not positive is empty");
        return csg::NodePtr();
    }
    if (auto faceted = cylinderPolytope(e, s, facets, h, r1, r2, center))
        return csg::leaf(std::move(*faceted), {leafTag(e, s, state), state.material});
    csg::NodePtr node = csg::leaf(csg::Cylinder{h, r1, r2}, {leafTag(e, s, state), state.material});
    if (center) node = csg::transformed(glm::translate(Mat4(1.0), Vec3(0, 0, -h / 2)), node);
    return node;
}

// torus(R, r): the ring torus of issue 5 around the z axis; D and d give diameters (d over
// r and D over R, as OpenSCAD's d over r). Not an OpenSCAD module, so there is no empty
// fallback: anything but R > r > 0 is an error naming the expected form.
Instance torus(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
               const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"R", "r", "D", "d"}, "torus(R, r) with R > r > 0");
    if (!(b.given(0) || b.given(2)) || !(b.given(1) || b.given(3)))
        e.fail(s.loc, "torus() needs both radii; expected " + std::string(b.form) +
                          " (or D, d for diameters)");
    const double major = b.given(2) ? numberArg(e, b, 2, 0.0) / 2.0 : numberArg(e, b, 0, 0.0);
    const double minor = b.given(3) ? numberArg(e, b, 3, 0.0) / 2.0 : numberArg(e, b, 1, 0.0);
    const csg::Torus shape{major, minor};
    if (shape.invalidReason())
        e.fail(s.loc, "torus(): R = " + formatNumber(major) + ", r = " + formatNumber(minor) +
                          " is not a ring torus; expected " + std::string(b.form));
    return csg::leaf(shape, {leafTag(e, s, state), state.material});
}

Instance halfspace(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                   const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"normal", "offset"}, "halfspace(normal, offset)");
    const Vec3 normal = vecArg(e, b, 0, Vec3(0, 0, 1), 0.0, false, false);
    const double offset = numberArg(e, b, 1, 0.0);
    if (normal == Vec3(0.0)) b.bad(e, 0, "a non-zero vector");
    return csg::leaf(csg::HalfSpace{normal, offset}, {leafTag(e, s, state), state.material});
}

// ---- booleans ----

Instance unionModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                     const GeomState& state) {
    // union, group and render are the same to a ray caster.
    // The form is a literal (BoundArgs keeps a view of it); the table maps these three here.
    const char* form = s.name == "group"    ? "group() { ... }"
                       : s.name == "render" ? "render() { ... }"
                                            : "union() { ... }";
    BoundArgs b = bindArgs(e, s, ctx, {"convexity"}, form);
    return childrenGroup(e, b, ctx, state);
}

Instance booleanModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                       const GeomState& state, bool isDifference) {
    BoundArgs b =
        bindArgs(e, s, ctx, {}, isDifference ? "difference() { ... }" : "intersection() { ... }");
    GeomState inner = state;
    inner.modulePath = e.childPath(state, s.name);
    bool any = false;
    auto parts = e.instantiateChildren(s, ctx, inner, b.all, any);
    if (!any) return std::nullopt;
    const csg::Tags tags{e.sourceTag(s.loc, inner.modulePath), 0};
    e.keepOneDimension(parts, tags.source);
    if (parts.empty()) return std::nullopt;
    if (isDifference) {
        // The first child minus all the others; empty children cut nothing.
        if (!parts[0]) return csg::NodePtr();
        std::vector<csg::NodePtr> cut;
        for (size_t i = 1; i < parts.size(); ++i)
            if (parts[i]) cut.push_back(parts[i]);
        if (cut.empty()) return parts[0];
        return csg::subtractAll(parts[0], cut, tags);
    }
    for (const auto& p : parts)
        if (!p) return csg::NodePtr();  // intersecting with nothing gives nothing
    return csg::intersectAll(parts, tags);
}

Instance difference(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state) {
    return booleanModule(e, s, ctx, state, true);
}
Instance intersection(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state) {
    return booleanModule(e, s, ctx, state, false);
}

// ---- transforms ----

// Whether m flattens space in the dimension of its children: its linear part's determinant
// is zero relative to its size (3x3 for solids, the x-y 2x2 for 2-D shapes, whose z OpenSCAD
// drops).
bool flattens(const Mat4& m, int dimension) {
    // Divided by its largest entry first, so that a tiny but regular scale (1e-200) does not
    // underflow (a column's length would).
    if (dimension == 2) {
        glm::dmat2 linear(m[0][0], m[0][1], m[1][0], m[1][1]);
        double size = 0.0;
        for (int c = 0; c < 2; ++c)
            for (int r = 0; r < 2; ++r) size = std::max(size, std::fabs(linear[c][r]));
        if (!(size > 0.0)) return true;
        linear /= size;
        return std::fabs(glm::determinant(linear)) <= csg::tol::kSingularDetRel;
    }
    csg::Mat3 linear(m);
    double size = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) size = std::max(size, std::fabs(linear[c][r]));
    if (!(size > 0.0)) return true;
    linear /= size;
    return std::fabs(glm::determinant(linear)) <= csg::tol::kSingularDetRel;
}

// The children seen through m. A transform that flattens space (a zero scale factor, a
// singular matrix) leaves its children no volume (no area, for 2-D ones): OpenSCAD 2021 drops
// them and goes on, and so does csgray, with a warning that says so (`what` names the
// transform). The children are still evaluated, for their echo()s and errors, as OpenSCAD does.
Instance applyTransform(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx,
                        const GeomState& state, const Mat4& m, const std::string& what = "") {
    GeomState inner = state;
    inner.worldFromHere = state.worldFromHere * m;
    Instance children = childrenGroup(e, b, ctx, inner);
    if (!children || !*children) return children;
    const int dimension = dimensionOf(*children);
    if (flattens(m, dimension)) {
        e.warn(b.call.loc, (what.empty() ? b.call.name + "()" : what) +
                               " flattens its children: they have no " +
                               (dimension == 2 ? "area" : "volume") +
                               " and are dropped, as in OpenSCAD");
        return csg::NodePtr();
    }
    if (dimension == 2) return transformed2D(m, *children);
    return csg::transformed(m, *children);
}

// The vector argument of translate or scale (identity: the default, which also fills a vec2's
// z). One OpenSCAD cannot read gives its warning and the identity.
Vec3 transformArg(Evaluator& e, const BoundArgs& b, Vec3 identity, bool allowScalar,
                  const char* what) {
    if (!b.given(0)) return identity;
    if (const std::optional<Vec3> read = transformVector(b[0], identity.z, allowScalar))
        return *read;
    e.warn(b.loc(0), "Unable to convert " + b.call.name + "(" + b[0].brief() + ") parameter to " +
                         what + "; " + b.call.name + "() ignored, as in OpenSCAD");
    return identity;
}

Instance translate(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                   const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"v"}, "translate(v)");
    const Vec3 v = transformArg(e, b, Vec3(0.0), false, "a vec3 or vec2 of numbers");
    return applyTransform(e, b, ctx, state, glm::translate(Mat4(1.0), v));
}

Mat4 rotationAbout(const Vec3& axis, double degrees) {
    const double c = cosDegrees(degrees), s = sinDegrees(degrees);
    const Vec3 u = glm::normalize(axis);
    // Rodrigues: c I + s [u]x + (1 - c) u u^T, written column by column (glm is column-major).
    Mat4 m(1.0);
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) m[col][row] = (1 - c) * u[row] * u[col];
    for (int k = 0; k < 3; ++k) m[k][k] += c;
    m[1][0] -= s * u.z;  // row 0, col 1
    m[2][0] += s * u.y;
    m[0][1] += s * u.z;
    m[2][1] -= s * u.x;
    m[0][2] -= s * u.y;
    m[1][2] += s * u.x;
    return m;
}

Instance rotate(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"a", "v"}, "rotate(a) or rotate([x, y, z]) or rotate(a, v)");
    Mat4 m(1.0);
    if (b.given(0) && b[0].isVector()) {
        // rotate([x, y, z]) = Rz * Ry * Rx: about x first. A shorter vector fills from x with
        // zeros; what OpenSCAD cannot read (entries past the third, non-numbers) it warns about
        // and reads as 0.
        const ValueList& l = b[0].list();
        Vec3 angles(0.0);
        bool readAll = l.size() <= 3;
        for (size_t k = 0; k < std::min<size_t>(l.size(), 3); ++k) {
            if (l[k].isNumber() && std::isfinite(l[k].number()))
                angles[static_cast<int>(k)] = l[k].number();
            else
                readAll = false;
        }
        if (!readAll)
            e.warn(b.loc(0), "Problem converting rotate(a=" + b[0].brief() + ") parameter");
        m = rotationAbout(Vec3(0, 0, 1), angles.z) * rotationAbout(Vec3(0, 1, 0), angles.y) *
            rotationAbout(Vec3(1, 0, 0), angles.x);
    } else if (b.given(0)) {
        const double a = numberArg(e, b, 0, 0.0);
        Vec3 axis(0, 0, 1);
        if (b.given(1)) axis = vecArg(e, b, 1, axis, 0.0, false, false);
        // A zero axis rotates nothing, as in OpenSCAD.
        if (axis != Vec3(0.0)) m = rotationAbout(axis, a);
    }
    return applyTransform(e, b, ctx, state, m);
}

Instance scale(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
               const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"v"}, "scale(v)");
    const Vec3 v = transformArg(e, b, Vec3(1.0), true, "a number, a vec3 or vec2 of numbers");
    return applyTransform(e, b, ctx, state, glm::scale(Mat4(1.0), v),
                          b.given(0) ? "scale(" + b[0].brief() + ")" : "");
}

Instance mirror(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"v"}, "mirror(v)");
    const Vec3 v = vecArg(e, b, 0, Vec3(1, 0, 0), 0.0, false);
    Mat4 m(1.0);
    if (v != Vec3(0.0)) {
        // Householder reflection I - 2 n n^T across the plane through the origin normal to v.
        const Vec3 n = glm::normalize(v);
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row) m[col][row] -= 2.0 * n[row] * n[col];
    }
    return applyTransform(e, b, ctx, state, m);
}

Instance multmatrix(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"m"}, "multmatrix(m) with m a 4x4 or 3x4 matrix of rows");
    Mat4 m(1.0);
    if (b.given(0) && b[0].isVector()) {
        // As OpenSCAD 2021 reads it: up to 4 rows of up to 4 numbers, every entry not given
        // (or not a number) taken from the identity; a last row [a, b, c, w] with w != 1
        // divides the whole matrix by w and is otherwise ignored (the map stays affine).
        const ValueList& rows = b[0].list();
        for (size_t row = 0; row < std::min<size_t>(rows.size(), 4); ++row) {
            if (!rows[row].isVector()) continue;
            const ValueList& r = rows[row].list();
            for (size_t col = 0; col < std::min<size_t>(r.size(), 4); ++col)
                if (r[col].isNumber())
                    m[static_cast<int>(col)][static_cast<int>(row)] = r[col].number();
        }
        const double w = m[3][3];
        m[0][3] = m[1][3] = m[2][3] = 0.0;
        m[3][3] = 1.0;
        if (w != 1.0)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 3; ++r) m[c][r] /= w;
        if (!csg::isFinite(m)) {
            e.warn(b.loc(0),
                   "Transformation matrix contains Not-a-Number and/or Infinity - removing "
                   "object.");
            return csg::NodePtr();
        }
    } else if (b.given(0)) {
        e.warn(b.loc(0), "multmatrix(" + b[0].brief() + "): not a matrix; multmatrix() ignored");
    }
    return applyTransform(e, b, ctx, state, m);
}

// ---- appearance ----

Instance color(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
               const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"c", "alpha"}, "color(c, alpha)");
    GeomState inner = state;
    Material m = e.model().materials[state.material];
    if (auto c = colorArg(e, b, 0)) m.color = *c;
    if (b.given(1)) m.color.a = numberArg(e, b, 1, 1.0);
    inner.material = e.internMaterial(m);
    return childrenGroup(e, b, ctx, inner);
}

// The index in Model::textures of the PNG written as `written` at argument i (relative to
// the file that names it), read on first use; an unreadable file is an error there.
int32_t textureArg(Evaluator& e, const BoundArgs& b, size_t i, const std::string& written) {
    if (!e.filesAllowed())
        e.fail(b.loc(i), "material(): cannot read texture \"" + written +
                             "\": reading files is not allowed here");
    std::filesystem::path path(written);
    if (path.is_relative()) path = e.filePath(b.loc(i).file).parent_path() / path;
    path = path.lexically_normal();
    std::vector<Model::Texture>& textures = e.model().textures;
    for (size_t k = 0; k < textures.size(); ++k)
        if (textures[k].path == path.string()) return int32_t(k);
    Model::Texture texture{path.string(), {}};
    if (std::string error = readPng(path, texture.image); !error.empty())
        e.fail(b.loc(i), "material(): texture " + error + "; expected texture=\"file.png\"");
    textures.push_back(std::move(texture));
    return int32_t(textures.size() - 1);
}

// material()'s pattern arguments (indices 8..11: pattern, color2, scale, texture). Fields
// not given keep the enclosing material's, like the coefficients; texture= alone implies
// pattern="texture".
void materialPattern(Evaluator& e, const BoundArgs& b, Material& m) {
    if (auto c = colorArg(e, b, 9)) m.color2 = *c;
    m.scale = numberArg(e, b, 10, m.scale);
    if (m.scale <= 0) b.bad(e, 10, "a number > 0 (world units)");
    if (b.given(11)) {
        if (!b[11].isString() || b[11].string().empty()) b.bad(e, 11, "a PNG file name");
        m.texture = textureArg(e, b, 11, b[11].string());
        m.pattern = Pattern::Texture;
    }
    if (!b.given(8)) return;
    const std::string name = b[8].isString() ? b[8].string() : std::string();
    if (name == "checker")
        m.pattern = Pattern::Checker;
    else if (name == "solid")
        m.pattern = Pattern::Solid;
    else if (name == "texture")
        m.pattern = Pattern::Texture;
    else
        b.bad(e, 8, "\"checker\", \"texture\" or \"solid\"");
    if (m.pattern == Pattern::Texture && m.texture < 0)
        e.fail(b.loc(8),
               "material(): pattern=\"texture\" needs an image; expected "
               "material(pattern=\"texture\", texture=\"file.png\", scale=s)");
}

Instance material(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                  const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx,
                           {"color", "ambient", "diffuse", "specular", "shininess", "reflect",
                            "transmit", "ior", "pattern", "color2", "scale", "texture"},
                           "material(color, ambient, diffuse, specular, shininess, reflect, "
                           "transmit, ior, pattern=\"checker\"|\"texture\"|\"solid\", color2, "
                           "scale, texture=\"file.png\")");
    // Fields not given keep the enclosing material's values (inner wins field by field).
    Material m = e.model().materials[state.material];
    if (auto c = colorArg(e, b, 0)) m.color = *c;
    double* fields[] = {&m.ambient, &m.diffuse,  &m.specular, &m.shininess,
                        &m.reflect, &m.transmit, &m.ior};
    for (size_t k = 0; k < 7; ++k) {
        *fields[k] = numberArg(e, b, k + 1, *fields[k]);
        if (*fields[k] < 0) b.bad(e, k + 1, "a number >= 0");
    }
    if (m.ior <= 0) b.bad(e, 7, "a number > 0");
    materialPattern(e, b, m);
    GeomState inner = state;
    inner.material = e.internMaterial(m);
    return childrenGroup(e, b, ctx, inner);
}

// ---- scene ----

// OpenSCAD's warning for children given to a module that takes none (often a missing
// semicolon: `cube(1) sphere(1);`); the children are ignored.
void warnIfChildren(Evaluator& e, const InstantiationStmt& s) {
    if (!s.children.empty())
        e.warn(s.loc, "module " + s.name + "() does not support child modules");
}

Instance noChildren(Evaluator& e, const InstantiationStmt& s) {
    warnIfChildren(e, s);
    return std::nullopt;
}

// A module that makes a solid of its own and takes no children.
template <Evaluator::BuiltinModule module>
Instance childless(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                   const GeomState& state) {
    warnIfChildren(e, s);
    return module(e, s, ctx, state);
}

Instance camera(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"eye", "center", "up", "fov", "projection"},
                           "camera(eye, center, up, fov, projection)");
    Camera c;
    c.eye = csg::transformPoint(state.worldFromHere, vecArg(e, b, 0, c.eye, 0.0, false, false));
    c.center =
        csg::transformPoint(state.worldFromHere, vecArg(e, b, 1, c.center, 0.0, false, false));
    c.up = csg::transformVector(state.worldFromHere, vecArg(e, b, 2, c.up, 0.0, false, false));
    c.fov = numberArg(e, b, 3, c.fov);
    if (c.fov <= 0 || c.fov >= 180) b.bad(e, 3, "an angle in (0, 180) degrees");
    if (b.given(4)) {
        if (b[4].isString() && b[4].string() == "perspective")
            c.projection = Projection::Perspective;
        else if (b[4].isString() && b[4].string() == "orthographic")
            c.projection = Projection::Orthographic;
        else
            b.bad(e, 4, "\"perspective\" or \"orthographic\"");
    }
    if (c.eye == c.center) e.fail(s.loc, "camera(): eye and center are the same point");
    if (e.model().camera) e.warn(s.loc, "more than one camera(); the last one is used");
    e.model().camera = c;
    return noChildren(e, s);
}

Instance light(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
               const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"position", "color", "intensity", "shadows"},
                           "light(position, color, intensity, shadows)");
    Light l;
    l.position =
        csg::transformPoint(state.worldFromHere, vecArg(e, b, 0, l.position, 0.0, false, false));
    if (auto c = colorArg(e, b, 1)) l.color = Vec3(*c);
    l.intensity = numberArg(e, b, 2, l.intensity);
    if (l.intensity < 0) b.bad(e, 2, "a number >= 0");
    l.shadows = boolArg(e, b, 3, l.shadows);
    e.model().lights.push_back(l);
    return noChildren(e, s);
}

Instance background(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                    const GeomState&) {
    BoundArgs b = bindArgs(e, s, ctx, {"color"}, "background(color)");
    if (!b.given(0)) e.fail(s.loc, "background() needs a color; expected background(color)");
    if (auto c = colorArg(e, b, 0)) e.model().background = Vec3(*c);
    return noChildren(e, s);
}

Instance unsupported(Evaluator& e, const InstantiationStmt& s, const ContextPtr&,
                     const GeomState&) {
    // The primitives' names, from the primitive set: "sphere, cube, ... and bezier_patches".
    static const std::string kPrimitiveList = [] {
        std::string list;
        for (size_t i = 0; i < csg::kPrimitiveNames.size(); ++i) {
            if (i > 0) list += i + 1 < csg::kPrimitiveNames.size() ? ", " : " and ";
            list += csg::kPrimitiveNames[i];
        }
        return list;
    }();
    e.fail(s.loc, "'" + s.name + "' is not supported by csgray (only 3-D CSG of " + kPrimitiveList +
                      " is)");
}

const std::unordered_map<std::string, Evaluator::BuiltinModule>& table() {
    static const std::unordered_map<std::string, Evaluator::BuiltinModule> modules = {
        {"cube", childless<cube>},
        {"sphere", childless<sphere>},
        {"cylinder", childless<cylinder>},
        {"halfspace", childless<halfspace>},
        {"torus", childless<torus>},
        {"surface", childless<surfaceModule>},
        {"bezier_patch", childless<bezierPatchModule>},
        {"bezier_patches", childless<bezierPatchesModule>},
        {"polyhedron", childless<polyhedronModule>},
        {"import", childless<importModule>},
        {"square", childless<squareModule>},
        {"circle", childless<circleModule>},
        {"polygon", childless<polygonModule>},
        {"text", childless<textModule>},
        {"linear_extrude", linearExtrudeModule},
        {"rotate_extrude", rotateExtrudeModule},
        {"offset", offsetModule},
        {"hull", hullModule},
        {"minkowski", minkowskiModule},
        {"projection", projectionModule},
        {"resize", resizeModule},
        {"union", unionModule},
        {"group", unionModule},
        {"render", unionModule},
        {"difference", difference},
        {"intersection", intersection},
        {"translate", translate},
        {"rotate", rotate},
        {"scale", scale},
        {"mirror", mirror},
        {"multmatrix", multmatrix},
        {"color", color},
        {"material", material},
        {"camera", camera},
        {"light", light},
        {"background", background},
        // OpenSCAD modules with no exact ray-cast counterpart yet: an error, never a skip.
        {"roof", unsupported},
        {"child", unsupported},
    };
    return modules;
}

}  // namespace

const Evaluator::BuiltinModule* Evaluator::findBuiltinModule(const std::string& name) const {
    const auto& t = table();
    auto it = t.find(name);
    return it == t.end() ? nullptr : &it->second;
}

}  // namespace io
