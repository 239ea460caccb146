// 3MF (3D Manufacturing Format, core specification 1.2): a zip package (io/mesh/Zip.h) of three
// parts, the content types, the relationship naming the model part, and the model: one object
// whose mesh is the part's welded vertices and its triangles, counter-clockwise seen from
// outside as the format requires, in millimetres (OpenSCAD's unit). The part's colours go into
// one basematerials group (sRGB as written in color(), with alpha), a triangle naming its own.
// Coordinates are the float values every other format writes, as their shortest exact text,
// so that compare measures the same mesh whatever the format.
#include <cmath>
#include <set>

#include "io/mesh/MeshFileDetail.h"
#include "io/mesh/Zip.h"
#include "primitives/base/AtomicFile.h"

namespace io::detail {
namespace {

constexpr const char* kContentTypes =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">\n"
    " <Default Extension=\"rels\" "
    "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>\n"
    " <Default Extension=\"model\" "
    "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\n"
    "</Types>\n";

constexpr const char* kRelationships =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\n"
    " <Relationship Id=\"rel0\" Target=\"/3D/3dmodel.model\" "
    "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>\n"
    "</Relationships>\n";

constexpr uint32_t kMaterialsId = 1, kObjectId = 2;

// "#RRGGBBAA" of an RGBA colour in [0, 1].
std::string displayColor(const csg::Vec4& c) {
    static const char* const kHex = "0123456789ABCDEF";
    std::string s = "#";
    for (int i = 0; i < 4; ++i) {
        const int byte = int(std::lround(std::clamp(c[i], 0.0, 1.0) * 255.0));
        s += kHex[byte >> 4];
        s += kHex[byte & 15];
    }
    return s;
}

constexpr const char* kModelOpen =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<model unit=\"millimeter\" xml:lang=\"en-US\" "
    "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n"
    " <metadata name=\"Application\">csgray</metadata>\n";

std::string modelXml(const csg::TriangleMesh& mesh, const std::vector<Material>& materials) {
    // An empty part is an empty build: a valid package with nothing for a printer to place.
    if (mesh.empty()) return std::string(kModelOpen) + " <resources/>\n <build/>\n</model>\n";

    // The materials the triangles use (a loaded mesh may have none: the default one), each a
    // base of the group by its position there.
    auto materialOf = [&](size_t t) {
        return mesh.triangleMaterial.empty() ? 0u : mesh.triangleMaterial[t];
    };
    std::set<uint32_t> used;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) used.insert(materialOf(t));
    std::vector<uint32_t> baseOf(*used.rbegin() + 1, 0);
    std::string out = std::string(kModelOpen) + " <resources>\n";
    out += "  <basematerials id=\"" + std::to_string(kMaterialsId) + "\">\n";
    uint32_t base = 0;
    for (const uint32_t id : used) {
        const Material m = id < materials.size() ? materials[id] : Material{};
        out += "   <base name=\"material_" + std::to_string(id) + "\" displaycolor=\"" +
               displayColor(m.color) + "\"/>\n";
        baseOf[id] = base++;
    }
    out += "  </basematerials>\n";
    out += "  <object id=\"" + std::to_string(kObjectId) + "\" type=\"model\" pid=\"" +
           std::to_string(kMaterialsId) + "\" pindex=\"" + std::to_string(baseOf[materialOf(0)]) +
           "\">\n   <mesh>\n    <vertices>\n";
    out.reserve(out.size() + 60 * mesh.positions.size() + 70 * mesh.triangles.size());
    for (const csg::Vec3& p : mesh.positions) {
        out += "     <vertex x=\"";
        appendNumber(out, float(p.x));
        out += "\" y=\"";
        appendNumber(out, float(p.y));
        out += "\" z=\"";
        appendNumber(out, float(p.z));
        out += "\"/>\n";
    }
    out += "    </vertices>\n    <triangles>\n";
    const bool perTriangle = used.size() > 1;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& v = mesh.triangles[t];
        out += "     <triangle v1=\"";
        appendNumber(out, v[0]);
        out += "\" v2=\"";
        appendNumber(out, v[1]);
        out += "\" v3=\"";
        appendNumber(out, v[2]);
        if (perTriangle) {
            out += "\" pid=\"" + std::to_string(kMaterialsId) + "\" p1=\"";
            appendNumber(out, baseOf[materialOf(t)]);
        }
        out += "\"/>\n";
    }
    out +=
        "    </triangles>\n   </mesh>\n  </object>\n </resources>\n <build>\n  <item objectid=\"" +
        std::to_string(kObjectId) + "\"/>\n </build>\n</model>\n";
    return out;
}

}  // namespace

std::optional<std::string> write3mf(const std::filesystem::path& file,
                                    const csg::TriangleMesh& mesh,
                                    const std::vector<Material>& materials) {
    std::vector<ZipEntry> parts(3);
    parts[0] = {"[Content_Types].xml", kContentTypes};
    parts[1] = {"_rels/.rels", kRelationships};
    parts[2] = {"3D/3dmodel.model", modelXml(mesh, materials)};
    const ZipWriteResult zip = writeZip(parts);
    if (!zip.error.empty()) return zip.error;
    if (std::string error = csg::writeFileAtomically(file, zip.archive); !error.empty())
        return error;
    return std::nullopt;
}

}  // namespace io::detail
