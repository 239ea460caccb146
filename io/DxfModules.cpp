// DXF drawings in the language: see io/DxfModules.h, and ../shared/OPENSCAD.md §2-4 for the
// OpenSCAD 2021 behaviour followed (src/import.cc, src/linearextrude.cc, src/rotateextrude.cc,
// src/dxfdim.cc).
#include "io/DxfModules.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/DataFiles.h"
#include "io/Degrees.h"
#include "io/DxfFile.h"
#include "io/FacetedPrimitives.h"
#include "primitives/Extrusion.h"

namespace io {

namespace {

using csg::Vec2;

// Evaluation steps charged per edge of a drawing (EvaluateOptions::maxSteps, ~5 bytes a step):
// an edge keeps a 100-byte segment, its grid nodes, cell entries and path points.
constexpr uint64_t kEdgeSteps = 50;

// Where a file name was written, with the DXF line when there is one: "x.dxf:12".
std::string where(const std::filesystem::path& path, uint32_t line) {
    return path.string() + (line > 0 ? ":" + std::to_string(line) : "");
}

// The reader's warnings and OpenSCAD's "Unsupported DXF Entity" ones, at the call.
void warnAbout(Evaluator& e, Loc loc, const std::string& what, const std::string& written,
               const std::filesystem::path& path, const DxfOptions& options,
               const DxfDrawing& drawing) {
    for (const DxfWarning& w : drawing.warnings)
        e.warn(loc, what + ": " + where(path, w.line) + ": " + w.message);
    for (const auto& [entity, count] : drawing.unsupported)
        e.warn(loc, "Unsupported DXF Entity '" + entity + "' (" + std::to_string(count) + ") in " +
                        (options.layer.empty() ? "\"" + written + "\"."
                                               : "layer '" + options.layer + "' of " + written));
}

// OpenSCAD's getVec2: a list of exactly two numbers (finite, here: OpenSCAD would go on with
// infinite coordinates).
std::optional<Vec2> vec2Of(const Value& v) {
    if (!v.isVector() || v.list().size() != 2) return std::nullopt;
    const ValueList& l = v.list();
    if (!l[0].isNumber() || !l[1].isNumber()) return std::nullopt;
    const Vec2 p(l[0].number(), l[1].number());
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::nullopt;
    return p;
}

// A layer name: a string, or a number as OpenSCAD prints it (layer = 0 is the layer "0").
std::optional<std::string> layerOf(const Value& v) {
    if (v.isUndef()) return std::string();
    if (v.isString()) return v.string();
    if (v.isNumber()) return formatNumber(v.number());
    return std::nullopt;
}

}  // namespace

bool isDxfFile(std::string_view name) {
    return lowerExtension(name) == ".dxf";
}

Instance dxfShape(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx, const GeomState& state,
                  const DxfArgs& args) {
    const std::string what = b.call.name + "()";
    const std::string& written = b[args.file].string();
    DxfOptions options;
    const std::optional<std::string> layer = layerOf(b[args.layer]);
    if (!layer) b.bad(e, args.layer, "a layer name");
    options.layer = *layer;
    if (b.given(args.origin)) {
        if (const auto origin = vec2Of(b[args.origin]))
            options.origin = *origin;
        else
            e.warn(b.loc(args.origin), b.call.name + "(..., origin=" + b[args.origin].brief() +
                                           ") could not be converted; [0, 0] is used, as in "
                                           "OpenSCAD");
    }
    options.scale = args.scale;
    const FragmentSettings settings = fragmentSettings(e, b, ctx);
    options.faceted = isFaceted(e.curveMode(), settings);
    options.fragments = settings;
    options.only2021 = e.curveMode() == CurveMode::OpenScad;
    options.maxEdges = e.budget().left / kEdgeSteps;
    if (!e.filesAllowed()) e.fail(b.loc(args.file), what + ": reading files is not allowed here");

    const std::filesystem::path path = lookupDataFile(e, b.call.loc, b.loc(args.file), written);
    DxfReadResult read = readDxfFile(path, options);
    if (!read.drawing)
        e.fail(b.loc(args.file), what + ": " + where(path, read.line) + ": " + read.error);
    e.spend(b.call.loc, kEdgeSteps * read.drawing->edges.size());
    warnAbout(e, b.call.loc, what, written, path, options, *read.drawing);
    csg::Outline outline = read.drawing->outline();
    if (outline.segments.empty()) return csg::NodePtr();
    const uint32_t tag = e.sourceTag(b.call.loc, e.childPath(state, b.call.name));
    return csg::leaf(
        csg::Extrusion::plane(std::make_shared<csg::Outline>(std::move(outline)), "import"),
        {tag, state.material});
}

Instance importDxf(Evaluator& e, const BoundArgs& b, const ContextPtr& ctx,
                   const GeomState& state) {
    // import(file, layer, convexity, origin, scale): a scale that is not above 0 is 1.
    if (b.given(2) && !b[2].isNumber()) b.bad(e, 2, "a number (a preview hint, ignored)");
    double scale = 1.0;
    if (b.given(4)) {
        if (!b[4].isNumber() || !std::isfinite(b[4].number())) b.bad(e, 4, "a finite number");
        scale = b[4].number();
        if (scale <= 0.0) {
            e.warn(b.loc(4), "import(): scale = " + formatNumber(scale) +
                                 " is taken as 1, as OpenSCAD takes a scale that is not above 0");
            scale = 1.0;
        }
    }
    return dxfShape(e, b, ctx, state, DxfArgs{0, 1, 3, scale});
}

namespace {

// A DXF function's arguments: named as OpenSCAD 2021 reads them, or (csgray) positional in the
// order of `names`. nullopt with OpenSCAD's warning when there is nothing to read.
struct FunctionArgs {
    std::filesystem::path path;
    std::string written;
    DxfOptions options;
    std::string name;  // dxf_dim's dimension name
};

std::optional<FunctionArgs> functionArgs(Evaluator& e, const ArgValues& args, Loc loc,
                                         const std::string& function,
                                         std::initializer_list<std::string_view> names) {
    FunctionArgs out;
    out.options.scale = 1.0;
    // OpenSCAD's DxfData(36, 0, 0, ...): 36 chords to a circle, whatever $fn, $fa, $fs are.
    out.options.faceted = true;
    out.options.fragments = FragmentSettings{36.0, 0.0, 0.0};
    out.options.only2021 = true;
    out.options.maxEdges = e.budget().left / kEdgeSteps;
    const Value* file = nullptr;
    Loc fileLoc = loc;
    bool warnedPositional = false;
    std::string order;  // "file, name, ..." for the warning
    for (std::string_view n : names) order += (order.empty() ? "" : ", ") + std::string(n);
    for (size_t i = 0; i < args.size(); ++i) {
        const ArgValue& a = args[i];
        std::string_view name = a.name;
        if (name.empty()) {
            if (i >= names.size()) {
                e.warn(a.loc, function + "(): argument " + std::to_string(i + 1) +
                                  " has no parameter (" + function + " has " +
                                  std::to_string(names.size()) + "); ignored");
                continue;
            }
            name = *(names.begin() + i);
            if (!warnedPositional)
                e.warn(a.loc, function +
                                  "(): OpenSCAD 2021 ignores unnamed arguments here (it "
                                  "reads named ones only); csgray takes them in the "
                                  "order " +
                                  order);
            warnedPositional = true;
        }
        const Value& v = a.value;
        if (name == "file") {
            file = &v;
            fileLoc = a.loc;
        } else if (name == "layer") {
            const auto layer = layerOf(v);
            if (!layer)
                e.warn(a.loc, function + "(..., layer=" + v.brief() + ") is not a layer name");
            else
                out.options.layer = *layer;
        } else if (name == "origin") {
            if (const auto origin = vec2Of(v))
                out.options.origin = *origin;
            else
                e.warn(a.loc, function + "(..., origin=" + v.brief() + ") could not be converted");
        } else if (name == "scale") {
            // OpenSCAD's getDouble: a number is the scale, anything else leaves it 1.
            if (v.isNumber() && std::isfinite(v.number()))
                out.options.scale = v.number();
            else
                e.warn(a.loc, function + "(..., scale=" + v.brief() + ") could not be converted");
        } else if (name == "name" && std::find(names.begin(), names.end(), "name") != names.end()) {
            if (v.isString())
                out.name = v.string();
            else
                out.name = v.isUndef() ? "" : v.isNumber() ? formatNumber(v.number()) : v.brief();
        } else {
            e.warn(a.loc, function + "(..., " + std::string(name) + "=...) is not supported");
        }
    }
    if (!file || !file->isString()) {
        e.warn(fileLoc, "Can't open DXF file '" + (file ? file->brief() : std::string()) + "'! (" +
                            function + "() needs file = \"drawing.dxf\")");
        return std::nullopt;
    }
    out.written = file->string();
    if (!e.filesAllowed()) e.fail(fileLoc, function + "(): reading files is not allowed here");
    out.path = lookupDataFile(e, loc, fileLoc, out.written);
    return out;
}

// The drawing, or nullopt with OpenSCAD's warning when the file cannot be read.
std::optional<DxfDrawing> functionDrawing(Evaluator& e, Loc loc, const std::string& function,
                                          const FunctionArgs& a) {
    DxfReadResult read = readDxfFile(a.path, a.options);
    if (read.unreadable) {
        e.warn(loc, "Can't open DXF file '" + a.written + "'!");
        return std::nullopt;
    }
    if (!read.drawing)
        e.fail(loc, function + "(): " + where(a.path, read.line) + ": " + read.error);
    e.spend(loc, kEdgeSteps * read.drawing->edges.size());
    warnAbout(e, loc, function + "()", a.written, a.path, a.options, *read.drawing);
    return std::move(read.drawing);
}

// OpenSCAD's atan2_degrees: whole degrees when within 3e-14 of them.
double atan2Degrees(double y, double x) {
    const double degrees = std::atan2(y, x) * 57.2957795130823208767;
    const double whole = std::round(degrees);
    return std::abs(degrees - whole) < 3.0e-14 ? whole : degrees;
}

}  // namespace

Value dxfDimFunction(Evaluator& e, const ArgValues& args, Loc loc) {
    const auto a =
        functionArgs(e, args, loc, "dxf_dim", {"file", "name", "layer", "origin", "scale"});
    if (!a) return Value();
    const auto drawing = functionDrawing(e, loc, "dxf_dim", *a);
    if (!drawing) return Value();
    for (const DxfDimension& d : drawing->dimensions) {
        if (!a->name.empty() && d.name != a->name) continue;
        const Vec2* c = d.coords;
        switch (d.type & 7) {
            case 0: {  // rotated, horizontal or vertical: the distance along the angle
                const Vec2 v = c[4] - c[3];
                return std::abs(v.x * openscadCosDegrees(d.angle) +
                                v.y * openscadSinDegrees(d.angle));
            }
            case 1: {  // aligned
                const Vec2 v = c[4] - c[3];
                return std::sqrt(v.x * v.x + v.y * v.y);
            }
            case 2: {  // angular, by OpenSCAD's atan2 of (dx, dy)
                const double a1 = atan2Degrees(c[0].x - c[5].x, c[0].y - c[5].y);
                const double a2 = atan2Degrees(c[4].x - c[3].x, c[4].y - c[3].y);
                return std::abs(a1 - a2);
            }
            case 3:
            case 4: {  // diameter or radius
                const Vec2 v = c[5] - c[0];
                return std::sqrt(v.x * v.x + v.y * v.y);
            }
            case 6:  // ordinate
                return (d.type & 64) ? c[3].x : c[3].y;
            default:
                break;  // 5 (angular 3 point) and 7
        }
        e.warn(loc, "Dimension '" + a->name + "' in '" + a->written + "', layer '" +
                        a->options.layer + "' has unsupported type!");
        return Value();
    }
    e.warn(loc, "Can't find dimension '" + a->name + "' in '" + a->written + "', layer '" +
                    a->options.layer + "'!");
    return Value();
}

Value dxfCrossFunction(Evaluator& e, const ArgValues& args, Loc loc) {
    const auto a = functionArgs(e, args, loc, "dxf_cross", {"file", "layer", "origin", "scale"});
    if (!a) return Value();
    const auto drawing = functionDrawing(e, loc, "dxf_cross", *a);
    if (!drawing) return Value();
    // The first two paths of one edge each, as lines through their points (in path order).
    Vec2 p[4];
    size_t j = 0;
    for (const DxfPath& path : drawing->paths) {
        if (path.points.size() != 2) continue;
        p[j++] = path.points[0];
        p[j++] = path.points[1];
        if (j < 4) continue;
        const double den =
            (p[3].y - p[2].y) * (p[1].x - p[0].x) - (p[3].x - p[2].x) * (p[1].y - p[0].y);
        if (den == 0) break;
        const double ua =
            ((p[3].x - p[2].x) * (p[0].y - p[2].y) - (p[3].y - p[2].y) * (p[0].x - p[2].x)) / den;
        return ValueList{p[0].x + ua * (p[1].x - p[0].x), p[0].y + ua * (p[1].y - p[0].y)};
    }
    e.warn(loc, "Can't find cross in '" + a->written + "', layer '" + a->options.layer + "'!");
    return Value();
}

}  // namespace io
