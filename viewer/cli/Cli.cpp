#include "viewer/cli/Cli.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace viewer {

const char* const kCommonOptionsHelp =
    "  -D name=value          override the part's top-level variable name (value is an\n"
    "                         expression, as with OpenSCAD's -D); may be repeated\n"
    "  --curves=MODE          what the curves of cylinder(), sphere(), circle() and\n"
    "                         rotate_extrude() become:\n"
    "                         auto (default): OpenSCAD's polygon or polyhedron, vertex for\n"
    "                           vertex, where $fn > 0 sets its facets (a $fn=6 nut trap stays\n"
    "                           hexagonal); the exact curve where OpenSCAD would take $fa and\n"
    "                           $fs;\n"
    "                         exact: every curve exact, $fn ignored;\n"
    "                         openscad: every curve faceted as OpenSCAD 2021 would, $fa and\n"
    "                           $fs included (to check against its meshes)\n"
    "                         linear_extrude of a polygon is the same solid in every\n"
    "                           mode; with twist or scale = [sx, sy] it is the exact\n"
    "                           solid (slices ignored) under auto and exact, and\n"
    "                           OpenSCAD's sliced polyhedron under openscad (its slices\n"
    "                           and triangles, from slices, $fn, $fa and $fs)\n"
    "                         import()ed SVG keeps its Beziers and arcs exact except\n"
    "                           under openscad (OpenSCAD's fixed chords; $fn ignored)\n"
    "  --accel=STRUCTURE      what organizes the objects of each union and the faces of\n"
    "                         each mesh (every choice gives the same answers, only the\n"
    "                         time and memory differ):\n"
    "                         sah (default): surface area heuristic BVH; median: median\n"
    "                         cut BVH; goldsmith-salmon: insertion BVH; grid: uniform grid\n"
    "                         (Amanatides-Woo walk); nonuniform-grid: recursive halving\n"
    "                         along x, y, z, walked as an octree; auto: the uniform grid\n"
    "                         for a union of 4096 or more objects spread evenly, SAH\n"
    "                         otherwise and over a mesh's faces (bench/README.md,\n"
    "                         spatial structures)\n"
    "  --bounds=KIND          what bounds each node of the tree (every choice gives the\n"
    "                         same answers): boxes (default): axis-aligned boxes, and balls\n"
    "                         around spheres; slabs: also Kay and Kajiya's slab polyhedra\n"
    "                         (planes along the four body diagonals) where they are\n"
    "                         tighter than the box, as around turned parts\n"
    "  --polygon-method=M     how a ray is tested against the triangles of polygon meshes\n"
    "                         (polyhedron(), import(), OpenSCAD's sliced extrusions):\n"
    "                         watertight (default): Woop, Benthin and Wald's test, exact\n"
    "                           at shared edges and vertices, flat facets;\n"
    "                         snyder, marchal: the ray-tracing lecture's two methods, each\n"
    "                           triangle alone in rounded arithmetic (a ray through an edge\n"
    "                           may count it twice or not at all), with normals interpolated\n"
    "                           across facets that meet at less than 30 degrees\n"
    "  --diagnostics=FORMAT   text (default): file:line:col: error: message on stderr;\n"
    "                         json: one JSON array of diagnostics on stderr\n"
    "  -h, --help             show this help\n";

std::optional<std::string> ArgCursor::option(std::string_view name) {
    if (done()) return std::nullopt;
    const std::string& arg = peek();
    if (arg == name) {
        if (index_ + 1 >= args_.size()) throw UsageError(std::string(name) + " needs a value");
        index_ += 2;
        return args_[index_ - 1];
    }
    if (arg.size() > name.size() && arg.starts_with(name) && arg[name.size()] == '=') {
        ++index_;
        return arg.substr(name.size() + 1);
    }
    return std::nullopt;
}

bool ArgCursor::flag(std::string_view name) {
    if (done() || peek() != name) return false;
    ++index_;
    return true;
}

bool ArgCursor::common(CommonOptions& options) {
    if (done()) return false;
    if (flag("--help") || flag("-h")) {
        options.help = true;
        return true;
    }
    // -D takes its value attached (-Dx=1) or as the next argument (-D x=1), like OpenSCAD.
    std::optional<std::string> define;
    if (peek().starts_with("-D") && peek().size() > 2) {
        define = take().substr(2);
    } else if (auto d = option("-D")) {
        define = std::move(d);
    }
    if (define) {
        const size_t eq = define->find('=');
        if (eq == 0 || eq == std::string::npos)
            throw UsageError("-D expects name=value, got '" + *define + "'");
        options.defines.emplace_back(define->substr(0, eq), define->substr(eq + 1));
        return true;
    }
    if (auto mode = option("--curves")) {
        const std::optional<io::CurveMode> curves = io::parseCurveMode(*mode);
        if (!curves)
            throw UsageError("--curves expects auto, exact or openscad, got '" + *mode + "'");
        options.curves = *curves;
        return true;
    }
    if (auto name = option("--accel")) {
        const std::optional<csg::Accel> accel = csg::parseAccel(*name);
        if (!accel)
            throw UsageError(
                "--accel expects sah, median, goldsmith-salmon, grid, "
                "nonuniform-grid or auto, got '" +
                *name + "'");
        options.accel = *accel;
        return true;
    }
    if (auto name = option("--bounds")) {
        if (*name != "boxes" && *name != "slabs")
            throw UsageError("--bounds expects boxes or slabs, got '" + *name + "'");
        options.slabs = *name == "slabs";
        return true;
    }
    if (auto name = option("--polygon-method")) {
        const std::optional<csg::PolygonMethod> method = csg::parsePolygonMethod(*name);
        if (!method)
            throw UsageError("--polygon-method expects watertight, snyder or marchal, got '" +
                             *name + "'");
        options.polygonMethod = *method;
        return true;
    }
    if (auto format = option("--diagnostics")) {
        if (*format == "json") {
            options.jsonDiagnostics = true;
        } else if (*format == "text") {
            options.jsonDiagnostics = false;
        } else {
            throw UsageError("--diagnostics expects text or json, got '" + *format + "'");
        }
        return true;
    }
    // "-" alone is not an option, but a part cannot come from stdin either: leave it to the
    // caller, which reports it.
    if (!peek().starts_with("-")) {
        if (!options.part.empty())
            throw UsageError("more than one part given: '" + options.part + "' and '" + peek() +
                             "'");
        options.part = take();
        return true;
    }
    return false;
}

namespace {

double parseNumber(std::string_view text, std::string_view what) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    // from_chars rejects a leading '+', which people do write.
    const char* begin = text.data();
    if (begin != end && *begin == '+') ++begin;
    const auto r = std::from_chars(begin, end, value);
    if (r.ec != std::errc() || r.ptr != end || !std::isfinite(value))
        throw UsageError(std::string(what) + ": '" + std::string(text) +
                         "' is not a finite number");
    return value;
}

}  // namespace

csg::Vec3 parseVec3(std::string_view text, std::string_view what) {
    csg::Vec3 v(0.0);
    size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const size_t comma = i < 2 ? text.find(',', start) : text.size();
        if (comma == std::string_view::npos || (i == 2 && text.find(',', start) != text.npos))
            throw UsageError(std::string(what) + " expects X,Y,Z (three numbers), got '" +
                             std::string(text) + "'");
        v[i] = parseNumber(text.substr(start, comma - start), what);
        start = comma + 1;
    }
    return v;
}

int parsePositiveInt(std::string_view text, std::string_view what, int maxValue) {
    int value = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || value <= 0 || value > maxValue)
        throw UsageError(std::string(what) + " expects an integer from 1 to " +
                         std::to_string(maxValue) + ", got '" + std::string(text) + "'");
    return value;
}

double parseNumberIn(std::string_view text, std::string_view what, double low, double high) {
    const double value = parseNumber(text, what);
    if (value < low || value > high) {
        char range[64];
        std::snprintf(range, sizeof range, "%g to %g", low, high);
        throw UsageError(std::string(what) + " expects a number from " + range + ", got '" +
                         std::string(text) + "'");
    }
    return value;
}

std::pair<int, int> parseSize(std::string_view text, std::string_view what) {
    const size_t x = text.find_first_of("xX");
    if (x == std::string_view::npos)
        throw UsageError(std::string(what) + " expects WxH (e.g. 800x600), got '" +
                         std::string(text) + "'");
    constexpr int kMaxSide = 32768;
    return {parsePositiveInt(text.substr(0, x), what, kMaxSide),
            parsePositiveInt(text.substr(x + 1), what, kMaxSide)};
}

void requirePart(const CommonOptions& options, std::string_view command) {
    if (options.part.empty())
        throw UsageError(std::string(command) + " needs a part file (csgray " +
                         std::string(command) + " PART ...)");
}

}  // namespace viewer
