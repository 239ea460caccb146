// OpenSCAD 2021's surface(file = ...): see io/HeightmapModule.h. The reading follows 2021's
// src/surface.cc (read_dat, convert_image) step for step, so that the same file gives the same
// grid, and the mesh has OpenSCAD's vertices exactly (x = column, y = row, each cell's centre
// at the mean of its four corners), so `csgray compare` against OpenSCAD's STL sees rounding.
#include "io/HeightmapModule.h"
#include "io/DataFiles.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "io/BoundArgs.h"
#include "viewer/render/PngReader.h"

namespace io {

namespace {

constexpr const char* kForm =
    "surface(file = \"heights.dat\" | \"image.png\", center = false, invert = false, "
    "convexity = 1)";

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
    return s;
}

// A token as boost::lexical_cast<double> reads it: the whole token a number (a leading '+'
// allowed), and finite here (OpenSCAD would take "nan" and build a broken mesh of it).
bool readNumber(std::string_view token, double& out) {
    if (!token.empty() && token[0] == '+') {
        token.remove_prefix(1);
        if (!token.empty() && (token[0] == '+' || token[0] == '-')) return false;
    }
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
    return ec == std::errc() && end == token.data() + token.size() && std::isfinite(out);
}

}  // namespace

DatRead parseDat(std::string_view text, const std::string& fileName) {
    DatRead out;
    std::vector<std::vector<double>> rows;
    uint64_t given = 0;
    // std::getline's flags as read_dat sees them: eof is set by the read that reaches the
    // end of the text without a newline, or that finds nothing left.
    size_t pos = 0;
    bool eof = false;
    auto getline = [&]() -> std::string_view {
        if (pos >= text.size()) {
            eof = true;
            return {};
        }
        const size_t newline = text.find('\n', pos);
        std::string_view line;
        if (newline == std::string_view::npos) {
            line = text.substr(pos);
            pos = text.size();
            eof = true;
        } else {
            line = text.substr(pos, newline - pos);
            pos = newline + 1;
        }
        return line;
    };
    bool stop = false;
    while (!eof && !stop) {
        std::string_view line;
        while (!eof && (line.empty() || line[0] == '#')) line = trimmed(getline());
        if (line.empty() && eof) break;
        std::vector<double> row;
        size_t at = 0;
        while (at < line.size()) {
            if (line[at] == ' ' || line[at] == '\t') {
                ++at;
                continue;
            }
            size_t end = at;
            while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
            const std::string_view token = line.substr(at, end - at);
            double v = 0.0;
            if (!readNumber(token, v)) {
                if (!eof)
                    out.warning = "Illegal value in '" + fileName + "': '" +
                                  std::string(token.substr(0, 40)) +
                                  "' is not a finite number; the rest of the file is ignored, "
                                  "as in OpenSCAD";
                stop = true;
                break;
            }
            if (++given > kMaxHeightmapPoints) {
                out.error = "'" + fileName + "' has more than " +
                            std::to_string(kMaxHeightmapPoints) +
                            " heights (the most csgray reads)";
                return out;
            }
            row.push_back(v);
            at = end;
        }
        // A row whose first token stopped the reading adds nothing (OpenSCAD keeps the
        // values read before the bad token, in their row).
        if (!row.empty() || !stop) rows.push_back(std::move(row));
    }
    // Rows and columns from the values given, as createGeometry counts them.
    Heightmap& map = out.map;
    for (size_t r = 0; r < rows.size(); ++r) {
        if (rows[r].empty()) continue;
        map.rows = int(r + 1);
        map.columns = std::max(map.columns, int(rows[r].size()));
    }
    if (uint64_t(map.rows) * uint64_t(map.columns) > kMaxHeightmapPoints) {
        out.error = "'" + fileName + "' spans " + std::to_string(map.rows) + " rows by " +
                    std::to_string(map.columns) + " columns, more than " +
                    std::to_string(kMaxHeightmapPoints) + " points (the most csgray reads)";
        return out;
    }
    map.heights.assign(size_t(map.rows) * size_t(map.columns), 0.0);
    for (int r = 0; r < map.rows; ++r)
        for (size_t c = 0; c < rows[size_t(r)].size(); ++c) {
            const double v = rows[size_t(r)][c];
            map.heights[size_t(r) * size_t(map.columns) + c] = v;
            map.lowest = map.any ? std::min(map.lowest, v) : v;
            map.any = true;
        }
    return out;
}

void heightmapMesh(const Heightmap& map, bool center, std::vector<csg::Vec3>& points,
                   csg::PolygonFaces& faces) {
    const int rows = map.rows, columns = map.columns;
    // OpenSCAD's expressions, so that every coordinate has the same bits as its STL's.
    const double ox = center ? -(columns - 1) / 2.0 : 0;
    const double oy = center ? -(rows - 1) / 2.0 : 0;
    const double base = map.base();
    points.clear();
    faces = csg::PolygonFaces();
    // Vertices: the grid's tops, then the cells' centres, then the base under each border
    // point (by its place on the border loop), then the base's centre.
    auto top = [&](int r, int c) { return uint32_t(r * columns + c); };
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) points.push_back({ox + c, oy + r, map.at(r, c)});
    const uint32_t firstCentre = uint32_t(points.size());
    for (int i = 1; i < rows; ++i)
        for (int j = 1; j < columns; ++j) {
            const double v1 = map.at(i - 1, j - 1), v2 = map.at(i - 1, j);
            const double v3 = map.at(i, j - 1), v4 = map.at(i, j);
            points.push_back({ox + j - 0.5, oy + i - 0.5, (v1 + v2 + v3 + v4) / 4});
        }
    auto centre = [&](int i, int j) {
        return firstCentre + uint32_t((i - 1) * (columns - 1) + (j - 1));
    };
    for (int i = 1; i < rows; ++i)
        for (int j = 1; j < columns; ++j) {
            const uint32_t v1 = top(i - 1, j - 1), v2 = top(i - 1, j), v3 = top(i, j - 1),
                           v4 = top(i, j), vx = centre(i, j);
            faces.add({v1, v2, vx});
            faces.add({v2, v4, vx});
            faces.add({v4, v3, vx});
            faces.add({v3, v1, vx});
        }
    // The border loop: along row 0, up the last column, back along the last row, down
    // column 0. Each border point gets its base vertex; each border step a wall quad.
    std::vector<std::pair<int, int>> loop;
    for (int c = 0; c < columns - 1; ++c) loop.push_back({0, c});
    for (int r = 0; r < rows - 1; ++r) loop.push_back({r, columns - 1});
    for (int c = columns - 1; c > 0; --c) loop.push_back({rows - 1, c});
    for (int r = rows - 1; r > 0; --r) loop.push_back({r, 0});
    const uint32_t firstBase = uint32_t(points.size());
    for (const auto& [r, c] : loop) points.push_back({ox + c, oy + r, base});
    const uint32_t baseCentre = uint32_t(points.size());
    points.push_back({ox + (columns - 1) / 2.0, oy + (rows - 1) / 2.0, base});
    const uint32_t n = uint32_t(loop.size());
    for (uint32_t k = 0; k < n; ++k) {
        const uint32_t next = (k + 1) % n;
        const uint32_t t0 = top(loop[k].first, loop[k].second);
        const uint32_t t1 = top(loop[next].first, loop[next].second);
        faces.add({firstBase + k, t0, t1, firstBase + next});
        // The bottom as a fan from its centre over the same border edges, so that every
        // edge of the mesh is shared (no T-junctions along the base).
        faces.add({baseCentre, firstBase + next, firstBase + k});
    }
}

bool isHeightmapCall(const InstantiationStmt& s) {
    size_t positional = 0;
    for (const Argument& a : s.args) {
        if (a.name == "file" || a.name == "center" || a.name == "invert" || a.name == "convexity")
            return true;
        if (a.name == "f" || a.name == "bbox" || a.name == "solver" || a.name == "tolerance" ||
            a.name == "polish")
            return false;
        if (a.name.empty() && positional++ == 1 && a.value && a.value->kind == ExprKind::Vector)
            return false;
    }
    return true;
}

namespace {

// center and invert as OpenSCAD reads them: used only when a boolean, else ignored.
bool flagArg(Evaluator& e, const BoundArgs& b, size_t i) {
    if (!b.given(i)) return false;
    if (b[i].isBool()) return b[i].asBool();
    e.warn(b.loc(i), "surface(): '" + std::string(b.names[i]) + "' is " + b[i].brief() +
                         ", not true or false; ignored, as in OpenSCAD");
    return false;
}

bool startsAsPng(const std::filesystem::path& path) {
    static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    std::ifstream in(path, std::ios::binary);
    char head[8] = {};
    return in.read(head, 8) && std::memcmp(head, kSignature, 8) == 0;
}

// The PNG's luminance as OpenSCAD 2021's convert_image computes it; image row y is grid row
// height - 1 - y (the top of the image at the largest y).
Heightmap pngHeights(const viewer::render::Rgb8Image& image, bool invert) {
    Heightmap map;
    map.rows = image.height;
    map.columns = image.width;
    map.heights.resize(size_t(map.rows) * size_t(map.columns));
    map.any = true;
    map.lowest = csg::kInfinity;
    for (int y = 0; y < image.height; ++y) {
        const uint8_t* p = image.pixels.data() + size_t(y) * size_t(image.width) * 3;
        for (int x = 0; x < image.width; ++x, p += 3) {
            const double pixel = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            const double z = 100.0 / 255 * (invert ? 1 - pixel : pixel);
            map.heights[size_t(image.height - 1 - y) * size_t(map.columns) + size_t(x)] = z;
            map.lowest = std::min(map.lowest, z);
        }
    }
    return map;
}

}  // namespace

Instance heightmapModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                         const GeomState& state) {
    // OpenSCAD 2021's positional order: file, center, convexity; invert by name.
    const BoundArgs b = bindArgs(e, s, ctx, {"file", "center", "convexity", "invert"}, kForm);
    if (!b.given(0))
        e.fail(s.loc,
               "surface() needs a file (or csgray's polynomial form surface(f = ..., "
               "bbox = ...)); expected " +
                   std::string(kForm));
    if (!b[0].isString()) b.bad(e, 0, "a file name");
    const bool center = flagArg(e, b, 1);
    const bool invert = flagArg(e, b, 3);
    const std::string& written = b[0].string();
    if (!e.filesAllowed()) e.fail(b.loc(0), "surface(): reading files is not allowed here");
    const std::filesystem::path path = lookupDataFile(e, s.loc, b.loc(0), written);

    Heightmap map;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        e.fail(b.loc(0), "surface(): cannot open '" + path.string() + "'; expected " + kForm);
    if (startsAsPng(path)) {
        viewer::render::Rgb8Image image;
        if (std::string why = viewer::render::readPngSamples(path, image, kMaxHeightmapPoints);
            !why.empty())
            e.fail(b.loc(0), "surface(): " + why);
        map = pngHeights(image, invert);
    } else {
        const uintmax_t bytes = std::filesystem::file_size(path, ec);
        if (ec || bytes > kMaxHeightmapFileBytes)
            e.fail(b.loc(0), "surface(): '" + path.string() + "' is " +
                                 (ec ? "unreadable"
                                     : "too large (" + std::to_string(bytes) + " bytes; at most " +
                                           std::to_string(kMaxHeightmapFileBytes) + ")"));
        std::string text(size_t(bytes), '\0');
        std::ifstream in(path, std::ios::binary);
        if (!in.read(text.data(), std::streamsize(bytes)))
            e.fail(b.loc(0), "surface(): cannot read '" + path.string() + "'");
        DatRead read = parseDat(text, written);
        if (!read.error.empty()) e.fail(b.loc(0), "surface(): " + read.error);
        if (!read.warning.empty()) e.warn(b.loc(0), read.warning);
        map = std::move(read.map);
    }
    e.spend(b.loc(0), uint64_t(map.rows) * uint64_t(map.columns));
    if (map.rows < 2 || map.columns < 2) {
        e.warn(b.loc(0), "surface(): '" + written + "' has " + std::to_string(map.rows) +
                             " rows and " + std::to_string(map.columns) +
                             " columns: a heightmap needs at least 2 of each; it is empty");
        return csg::NodePtr();
    }
    std::vector<csg::Vec3> points;
    csg::PolygonFaces faces;
    heightmapMesh(map, center, points, faces);
    const csg::Polyhedron mesh = csg::Polyhedron::make(std::move(points), faces);
    if (const char* why = mesh.invalidReason())
        e.fail(b.loc(0), "surface(): '" + written + "': " + why);
    return csg::leaf(mesh, {e.sourceTag(s.loc, e.childPath(state, s.name)), state.material});
}

}  // namespace io
