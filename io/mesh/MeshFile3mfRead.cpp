// Reading 3MF (core specification 1.2): the package's model part, found by its relationship in
// _rels/.rels, read with a small XML scanner that knows only what a mesh needs: objects with
// <vertices> and <triangles>, objects built of <component>s, and the <build> <item>s that place
// them, each transform applied (a mirroring one reverses the corners, so outside stays
// outside), in millimetres by the model's unit. Materials, metadata and extensions are skipped.
// Errors name the part and the line and column inside it.
#include <algorithm>
#include <charconv>
#include <map>
#include <optional>

#include "io/mesh/MeshFileDetail.h"
#include "io/mesh/MeshTextScanner.h"
#include "io/mesh/Zip.h"

namespace io::detail {
namespace {

// A placement of an object: its 3MF transform as a column-vector matrix.
using Transform = glm::dmat4;

// Instances are expanded, so a small file could ask for a vast mesh; past this many vertices
// (1.2 GB of positions) reading stops with an error instead of running out of memory.
constexpr size_t kMaxExpandedVertices = 50'000'000;
// Components may nest; deeper than this is taken for a cycle.
constexpr int kMaxComponentDepth = 32;

// One XML tag at a time: its local name (any namespace prefix dropped), its attributes, and
// whether it closes an element. Text, comments, processing instructions and declarations are
// stepped over.
class XmlScanner {
public:
    explicit XmlScanner(std::string_view text) : text_(text) {}

    struct Tag {
        std::string_view name;
        bool end = false;    // </name>
        bool empty = false;  // <name ... />
        size_t at = 0;       // the '<'
        std::vector<std::pair<std::string_view, std::string_view>> attributes;

        std::optional<std::string_view> attribute(std::string_view key) const {
            for (const auto& [k, v] : attributes)
                if (k == key) return v;
            return std::nullopt;
        }
    };

    // The next tag, false at the end of the text; on malformed XML false with error() set.
    bool next(Tag& tag) {
        while (true) {
            const size_t open = text_.find('<', pos_);
            if (open == std::string_view::npos) return false;
            pos_ = open;
            if (skipped("<?", "?>") || skipped("<!--", "-->") || skipped("<![CDATA[", "]]>") ||
                skipped("<!", ">")) {
                if (!error_.empty()) return false;
                continue;
            }
            tag = Tag{};
            tag.at = open;
            size_t i = open + 1;
            if (i < text_.size() && text_[i] == '/') {
                tag.end = true;
                ++i;
            }
            tag.name = localName(nameAt(i));
            if (tag.name.empty()) return fail(open, "expected an element name after '<'");
            while (true) {
                i = skipSpace(i);
                if (i >= text_.size()) return fail(open, "a tag is not closed by '>'");
                if (text_[i] == '>') break;
                if (text_.compare(i, 2, "/>") == 0) {
                    tag.empty = true;
                    ++i;
                    break;
                }
                const std::string_view key = nameAt(i);
                if (key.empty()) return fail(i, "expected an attribute name");
                i = skipSpace(i);
                if (i >= text_.size() || text_[i] != '=')
                    return fail(i, "expected '=' after the attribute name");
                i = skipSpace(i + 1);
                if (i >= text_.size() || (text_[i] != '"' && text_[i] != '\''))
                    return fail(i, "expected a quoted attribute value");
                const size_t close = text_.find(text_[i], i + 1);
                if (close == std::string_view::npos)
                    return fail(i, "an attribute value is not closed");
                tag.attributes.emplace_back(localName(key), text_.substr(i + 1, close - i - 1));
                i = close + 1;
            }
            pos_ = i + 1;
            return true;
        }
    }

    const std::string& error() const { return error_; }
    size_t errorAt() const { return errorAt_; }
    bool fail(size_t at, std::string message) {
        if (error_.empty()) {
            error_ = std::move(message);
            errorAt_ = at;
        }
        return false;
    }

private:
    // Steps over a construct from open to close at the cursor; an unclosed one is an error.
    bool skipped(std::string_view open, std::string_view close) {
        if (text_.compare(pos_, open.size(), open) != 0) return false;
        const size_t end = text_.find(close, pos_ + open.size());
        if (end == std::string_view::npos) {
            fail(pos_, "'" + std::string(open) + "' is not closed by '" + std::string(close) + "'");
            pos_ = text_.size();
        } else {
            pos_ = end + close.size();
        }
        return true;
    }
    size_t skipSpace(size_t i) const {
        while (i < text_.size() &&
               (text_[i] == ' ' || text_[i] == '\t' || text_[i] == '\n' || text_[i] == '\r'))
            ++i;
        return i;
    }
    // The XML name at i (advancing i past it).
    std::string_view nameAt(size_t& i) const {
        const size_t start = i;
        while (i < text_.size() &&
               (std::isalnum(static_cast<unsigned char>(text_[i])) || text_[i] == ':' ||
                text_[i] == '_' || text_[i] == '-' || text_[i] == '.'))
            ++i;
        return text_.substr(start, i - start);
    }
    static std::string_view localName(std::string_view name) {
        const size_t colon = name.rfind(':');
        return colon == std::string_view::npos ? name : name.substr(colon + 1);
    }

    std::string_view text_;
    size_t pos_ = 0;
    std::string error_;
    size_t errorAt_ = 0;
};

// A number as 3MF writes it (ST_Number: an optional sign, digits, fraction, exponent).
bool parseNumber(std::string_view s, double& value) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && end == s.data() + s.size() && measurable(value);
}
bool parseIndex(std::string_view s, uint32_t& value) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

// "m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32": row vectors times the 4x3 matrix, so
// x' = m00 x + m10 y + m20 z + m30, i.e. (m00, m01, m02) is the image of the x axis.
bool parseTransform(std::string_view s, Transform& m) {
    double v[12];
    for (int k = 0; k < 12; ++k) {
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
        const size_t stop = std::min(s.find(' '), s.size());
        if (!parseNumber(s.substr(0, stop), v[k])) return false;
        s.remove_prefix(stop);
    }
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    if (!s.empty()) return false;
    m = Transform(1.0);
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 3; ++row) m[col][row] = v[3 * col + row];
    return true;
}

struct Object {
    std::vector<csg::Vec3> vertices;
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<std::pair<uint32_t, Transform>> components;  // object id, placement
    bool support = false;  // type="support": printing aid, not part of the solid
};

// The millimetres in one unit of the model (ST_Unit).
std::optional<double> unitScale(std::string_view unit) {
    if (unit == "micron") return 0.001;
    if (unit == "millimeter") return 1.0;
    if (unit == "centimeter") return 10.0;
    if (unit == "inch") return 25.4;
    if (unit == "foot") return 304.8;
    if (unit == "meter") return 1000.0;
    return std::nullopt;
}

// The model part's path from the package relationships (the 3dmodel relationship's target),
// or the conventional one when there are none.
std::string modelPartName(const std::vector<ZipEntry>& entries) {
    for (const ZipEntry& e : entries) {
        if (!sameWord(e.name, "_rels/.rels")) continue;  // part names ignore case
        XmlScanner rels(e.bytes);
        XmlScanner::Tag tag;
        while (rels.next(tag)) {
            if (tag.name != "Relationship" || tag.end) continue;
            const auto type = tag.attribute("Type"), target = tag.attribute("Target");
            if (type && target && type->ends_with("/3dmodel")) {
                std::string_view path = *target;
                if (path.starts_with('/')) path.remove_prefix(1);
                return std::string(path);
            }
        }
    }
    return "3D/3dmodel.model";
}

class ModelReader {
public:
    explicit ModelReader(std::string_view text) : text_(text), xml_(text) {}

    // Reads the objects and the build, then expands the build into mesh.
    bool read(PolygonMesh& mesh) {
        XmlScanner::Tag tag;
        Object* object = nullptr;
        bool inBuild = false, sawModel = false;
        double scale = 1.0;
        while (xml_.next(tag)) {
            if (tag.end) {
                if (tag.name == "object") object = nullptr;
                if (tag.name == "build") inBuild = false;
                continue;
            }
            if (tag.name == "model") {
                sawModel = true;
                if (const auto unit = tag.attribute("unit")) {
                    const auto s = unitScale(*unit);
                    if (!s) return xml_.fail(tag.at, "unknown unit '" + std::string(*unit) + "'");
                    scale = *s;
                }
            } else if (tag.name == "object") {
                uint32_t id = 0;
                if (!parseIndex(tag.attribute("id").value_or(""), id))
                    return xml_.fail(tag.at, "an object needs a numeric id");
                if (objects_.count(id))
                    return xml_.fail(tag.at, "object id " + std::to_string(id) + " is used twice");
                object = &objects_[id];
                object->support = tag.attribute("type").value_or("") == "support";
                if (tag.empty) object = nullptr;
            } else if (tag.name == "vertex" && object) {
                double xyz[3];
                const char* names[3] = {"x", "y", "z"};
                for (int a = 0; a < 3; ++a)
                    if (!parseNumber(tag.attribute(names[a]).value_or(""), xyz[a]))
                        return xml_.fail(tag.at, std::string("a vertex needs a finite number ") +
                                                     names[a] + " within ±1e30");
                object->vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
            } else if (tag.name == "triangle" && object) {
                std::array<uint32_t, 3> v;
                const char* names[3] = {"v1", "v2", "v3"};
                for (int c = 0; c < 3; ++c)
                    if (!parseIndex(tag.attribute(names[c]).value_or(""), v[size_t(c)]) ||
                        v[size_t(c)] >= object->vertices.size())
                        return xml_.fail(tag.at, std::string("a triangle's ") + names[c] +
                                                     " names no vertex (" +
                                                     std::to_string(object->vertices.size()) +
                                                     " in its object)");
                object->triangles.push_back(v);
            } else if (tag.name == "component" && object) {
                if (tag.attribute("path"))
                    return xml_.fail(tag.at,
                                     "components in other parts (the production extension) "
                                     "are not read");
                std::pair<uint32_t, Transform> c{0, Transform(1.0)};
                if (!placement(tag, c)) return false;
                object->components.push_back(c);
            } else if (tag.name == "build") {
                inBuild = !tag.empty;
            } else if (tag.name == "item" && inBuild) {
                std::pair<uint32_t, Transform> item{0, Transform(1.0)};
                if (!placement(tag, item)) return false;
                items_.push_back({item, tag.at});
            }
        }
        if (!xml_.error().empty()) return false;
        if (!sawModel) return xml_.fail(0, "no <model> element");

        Transform unit(1.0);
        for (int a = 0; a < 3; ++a) unit[a][a] = scale;
        for (const auto& [item, at] : items_)
            if (!expand(item.first, unit * item.second, 0, at, mesh)) return false;
        return true;
    }

    std::string error() const { return xml_.error(); }
    // The 1-based line and column of the error in the model part.
    std::pair<uint32_t, uint32_t> errorLineColumn() const {
        const std::string_view before = text_.substr(0, std::min(xml_.errorAt(), text_.size()));
        const size_t newline = before.rfind('\n');
        const uint32_t line = uint32_t(std::count(before.begin(), before.end(), '\n') + 1);
        const uint32_t column = uint32_t(
            newline == std::string_view::npos ? before.size() + 1 : before.size() - newline);
        return {line, column};
    }

private:
    bool placement(const XmlScanner::Tag& tag, std::pair<uint32_t, Transform>& out) {
        if (!parseIndex(tag.attribute("objectid").value_or(""), out.first))
            return xml_.fail(tag.at, "<" + std::string(tag.name) + "> needs a numeric objectid");
        if (const auto t = tag.attribute("transform"); t && !parseTransform(*t, out.second))
            return xml_.fail(tag.at, "a transform is 12 finite numbers");
        return true;
    }

    bool expand(uint32_t id, const Transform& m, int depth, size_t at, PolygonMesh& mesh) {
        const auto found = objects_.find(id);
        if (found == objects_.end())
            return xml_.fail(at, "object " + std::to_string(id) + " is not defined");
        if (depth > kMaxComponentDepth)
            return xml_.fail(at, "components nest deeper than " +
                                     std::to_string(kMaxComponentDepth) + " (a cycle?)");
        const Object& object = found->second;
        if (object.support) return true;
        if (mesh.positions.size() + object.vertices.size() > kMaxExpandedVertices)
            return xml_.fail(at, "the build expands to over " +
                                     std::to_string(kMaxExpandedVertices) + " vertices");
        const uint32_t first = uint32_t(mesh.positions.size());
        for (const csg::Vec3& p : object.vertices) {
            const csg::Vec3 q = csg::Vec3(m * glm::dvec4(p, 1.0));
            if (!measurable(q)) return xml_.fail(at, kUnmeasurableCoordinate);
            mesh.positions.push_back(q);
        }
        const bool mirrored = glm::determinant(glm::dmat3(m)) < 0.0;
        for (const auto& t : object.triangles) {
            if (mirrored)
                mesh.faces.add({first + t[0], first + t[2], first + t[1]});
            else
                mesh.faces.add({first + t[0], first + t[1], first + t[2]});
        }
        for (const auto& [child, placed] : object.components)
            if (!expand(child, m * placed, depth + 1, at, mesh)) return false;
        return true;
    }

    std::string_view text_;
    XmlScanner xml_;
    std::map<uint32_t, Object> objects_;
    std::vector<std::pair<std::pair<uint32_t, Transform>, size_t>> items_;
};

}  // namespace

PolygonMeshReadResult parse3mf(std::string_view bytes) {
    PolygonMeshReadResult result;
    const ZipReadResult zip = readZip(bytes);
    if (!zip.error.empty()) {
        result.error = "3MF: " + zip.error;
        return result;
    }
    const std::string partName = modelPartName(zip.entries);
    const auto part = std::find_if(zip.entries.begin(), zip.entries.end(),
                                   [&](const ZipEntry& e) { return sameWord(e.name, partName); });
    if (part == zip.entries.end()) {
        result.error = "3MF: the package has no model part '" + partName + "'";
        return result;
    }
    ModelReader reader(part->bytes);
    PolygonMesh mesh;
    if (!reader.read(mesh)) {
        result.error = "3MF part '" + partName + "': " + reader.error();
        std::tie(result.line, result.column) = reader.errorLineColumn();
        return result;
    }
    result.mesh = std::move(mesh);
    return result;
}

}  // namespace io::detail
