// STL and 3MF (io/mesh/MeshFile.h) and the zip package under 3MF (io/mesh/Zip.h): what the
// writers put in the file, checked byte by byte where the format fixes it; 3MF's build items,
// components, units and mirrors placed as the specification says; broken packages refused
// with their reason, never a crash. OpenSCAD reading csgray's files, and csgray reading
// OpenSCAD's, is in cli_mesh_test.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "TextFiles.h"
#include "csg/mesh/MeshCheck.h"
#include "io/mesh/MeshFile.h"
#include "io/mesh/Zip.h"

namespace {

namespace fs = std::filesystem;
using csg::testing::readFile;
using csg::testing::writeFile;

class MeshFormats : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("mesh_formats_test_" +
                std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

// The regular tetrahedron (volume 8/3), outward triangles, two materials.
csg::TriangleMesh tetrahedron() {
    csg::TriangleMesh m;
    m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    m.triangleMaterial = {1, 1, 2, 1};
    return m;
}

std::vector<io::Material> redAndHalfBlue() {
    std::vector<io::Material> materials(3);
    materials[1].color = {1.0, 0.0, 0.0, 1.0};
    materials[2].color = {0.0, 0.0, 1.0, 0.5};
    return materials;
}

float floatAt(const std::string& bytes, size_t at) {
    float f;
    std::memcpy(&f, bytes.data() + at, 4);  // x86-64 is little-endian, as STL
    return f;
}

TEST_F(MeshFormats, BinaryStlIsEightyFourPlusFiftyBytesPerFacetWithRightHandNormals) {
    const fs::path file = dir_ / "t.stl";
    ASSERT_FALSE(io::writeMesh(file, tetrahedron(), {}).has_value());
    const std::string bytes = readFile(file);
    ASSERT_EQ(bytes.size(), 84u + 50u * 4u);
    EXPECT_NE(bytes.substr(0, 5), "solid");  // else readers take it for ASCII
    uint32_t count;
    std::memcpy(&count, bytes.data() + 80, 4);
    EXPECT_EQ(count, 4u);
    // Facet 0, (1,1,1), (1,-1,-1), (-1,1,-1), faces away from the fourth corner (-1,-1,1):
    // its normal is (1,1,-1)/sqrt(3). Its corners follow at bytes 96, 108 and 120.
    const float n = float(1.0 / std::sqrt(3.0));
    EXPECT_NEAR(floatAt(bytes, 84), n, 1e-7);
    EXPECT_NEAR(floatAt(bytes, 88), n, 1e-7);
    EXPECT_NEAR(floatAt(bytes, 92), -n, 1e-7);
    EXPECT_EQ(floatAt(bytes, 96), 1.0f);
    EXPECT_EQ(floatAt(bytes, 120), -1.0f);
    EXPECT_EQ(floatAt(bytes, 124), 1.0f);
    const io::MeshReadResult back = io::readMesh(file);
    ASSERT_TRUE(back.mesh) << back.error;
    EXPECT_EQ(back.mesh->positions.size(), 4u);
    EXPECT_NEAR(csg::signedVolume(*back.mesh), 8.0 / 3.0, 1e-12);
}

TEST_F(MeshFormats, AsciiStlReadsBackToTheSameFloatsAsBinary) {
    csg::TriangleMesh m = tetrahedron();
    for (csg::Vec3& p : m.positions) p *= 0.1;  // 0.1 is not a float: written as its float
    const fs::path file = dir_ / "t.stl";
    io::MeshWriteOptions ascii;
    ascii.asciiStl = true;
    ASSERT_FALSE(io::writeMesh(file, m, {}, ascii).has_value());
    const std::string text = readFile(file);
    EXPECT_EQ(text.rfind("solid csgray\n", 0), 0u) << text;
    EXPECT_NE(text.find("vertex 0.1 0.1 0.1\n"), std::string::npos) << text;  // shortest form
    const io::MeshReadResult back = io::readMesh(file);
    ASSERT_TRUE(back.mesh) << back.error;
    ASSERT_EQ(back.mesh->positions.size(), 4u);
    // The shortest text of a float reads back as that float (as a double it is the decimal).
    for (const csg::Vec3& p : back.mesh->positions)
        for (int a = 0; a < 3; ++a) EXPECT_EQ(float(std::abs(p[a])), 0.1f);
    EXPECT_TRUE(csg::checkTopology(*back.mesh).closedManifold());
}

TEST_F(MeshFormats, ZipEntriesRoundTripDeflatedOrStored) {
    std::mt19937 random(7);
    std::string noise(5000, '\0');
    for (char& c : noise) c = char(random());
    std::string xml;
    for (int i = 0; i < 2000; ++i) xml += "<vertex x=\"" + std::to_string(i) + "\"/>\n";
    const std::vector<io::ZipEntry> entries = {
        {"a.txt", "hello"}, {"dir/noise.bin", noise}, {"dir/x.xml", xml}, {"empty", ""}};
    const io::ZipWriteResult zip = io::writeZip(entries);
    ASSERT_TRUE(zip.error.empty()) << zip.error;
    EXPECT_LT(zip.archive.size(), noise.size() + xml.size() / 4);  // the XML deflated
    EXPECT_EQ(zip.archive.substr(0, 4), std::string("PK\x03\x04", 4));
    const io::ZipReadResult back = io::readZip(zip.archive);
    ASSERT_TRUE(back.error.empty()) << back.error;
    ASSERT_EQ(back.entries.size(), entries.size());
    for (size_t i = 0; i < entries.size(); ++i) {
        EXPECT_EQ(back.entries[i].name, entries[i].name);
        EXPECT_EQ(back.entries[i].bytes, entries[i].bytes) << entries[i].name;
    }
    // Reproducible: the same entries give the same bytes (no clock in the dates).
    EXPECT_EQ(io::writeZip(entries).archive, zip.archive);
}

TEST_F(MeshFormats, BrokenZipIsAnErrorNeverACrash) {
    std::string xml;
    for (int i = 0; i < 300; ++i) xml += "<triangle v1=\"" + std::to_string(i) + "\"/>\n";
    const std::vector<io::ZipEntry> entries = {{"3D/3dmodel.model", xml}, {"b", "stored"}};
    const std::string archive = io::writeZip(entries).archive;
    // Every truncation loses the end record or what it points to.
    for (size_t n = 0; n < archive.size(); ++n)
        EXPECT_FALSE(io::readZip(archive.substr(0, n)).error.empty()) << n;
    // Every single-bit flip: an error, or (a flip in a field that carries no data, such as
    // a date) the same bytes, which the CRC-32 proves.
    size_t errors = 0;
    for (size_t at = 0; at < archive.size(); ++at)
        for (int bit = 0; bit < 8; bit += 3) {
            std::string flipped = archive;
            flipped[at] = char(flipped[at] ^ (1 << bit));
            const io::ZipReadResult r = io::readZip(flipped);
            if (!r.error.empty()) {
                ++errors;
                continue;
            }
            ASSERT_EQ(r.entries.size(), entries.size()) << at;
            for (size_t i = 0; i < entries.size(); ++i)
                EXPECT_EQ(r.entries[i].bytes, entries[i].bytes) << at << " bit " << bit;
        }
    EXPECT_GT(errors, archive.size());  // most flips break something
    // A claimed size deflate cannot reach is refused before it is allocated.
    std::string bomb = archive;
    const size_t central = archive.rfind(std::string("PK\x01\x02", 4));
    const size_t first = archive.find(std::string("PK\x01\x02", 4));
    ASSERT_NE(first, std::string::npos);
    ASSERT_NE(central, std::string::npos);
    for (int i = 0; i < 4; ++i) bomb[first + 24 + size_t(i)] = char(0x7f);  // ~2 GB
    EXPECT_NE(io::readZip(bomb).error.find("more than deflate can produce"), std::string::npos)
        << io::readZip(bomb).error;
}

TEST_F(MeshFormats, ThreeMfRoundTripsWithTheColoursAsBaseMaterials) {
    const fs::path file = dir_ / "t.3mf";
    ASSERT_FALSE(io::writeMesh(file, tetrahedron(), redAndHalfBlue()).has_value());
    const io::ZipReadResult zip = io::readZip(readFile(file));
    ASSERT_TRUE(zip.error.empty()) << zip.error;
    ASSERT_EQ(zip.entries.size(), 3u);
    EXPECT_EQ(zip.entries[0].name, "[Content_Types].xml");
    EXPECT_EQ(zip.entries[1].name, "_rels/.rels");
    const std::string& model = zip.entries[2].bytes;
    EXPECT_NE(model.find("unit=\"millimeter\""), std::string::npos);
    EXPECT_NE(model.find("displaycolor=\"#FF0000FF\""), std::string::npos) << model;
    EXPECT_NE(model.find("displaycolor=\"#0000FF80\""), std::string::npos) << model;  // 0.5: 128
    // Triangle 2 is the blue one, the second base; the others the first.
    EXPECT_NE(model.find("<triangle v1=\"0\" v2=\"2\" v3=\"3\" pid=\"1\" p1=\"1\"/>"),
              std::string::npos)
        << model;
    EXPECT_NE(model.find("<triangle v1=\"0\" v2=\"1\" v3=\"2\" pid=\"1\" p1=\"0\"/>"),
              std::string::npos)
        << model;
    const io::MeshReadResult back = io::readMesh(file);
    ASSERT_TRUE(back.mesh) << back.error;
    EXPECT_EQ(back.mesh->positions, tetrahedron().positions);
    EXPECT_EQ(back.mesh->triangles, tetrahedron().triangles);
    // An empty part: a package with an empty build, read back as an empty mesh.
    ASSERT_FALSE(io::writeMesh(dir_ / "e.3mf", csg::TriangleMesh{}, {}).has_value());
    const io::MeshReadResult empty = io::readMesh(dir_ / "e.3mf");
    ASSERT_TRUE(empty.mesh) << empty.error;
    EXPECT_TRUE(empty.mesh->empty());
}

// A 3MF package of one model part (at the conventional path, with no relationships part).
fs::path packageOf(const fs::path& file, const std::string& model) {
    writeFile(file, io::writeZip({{"3D/3dmodel.model", model}}).archive);
    return file;
}

const char* const kTetObject =
    "  <object id=\"1\" type=\"model\"><mesh><vertices>\n"
    "   <vertex x=\"1\" y=\"1\" z=\"1\"/><vertex x=\"1\" y=\"-1\" z=\"-1\"/>\n"
    "   <vertex x=\"-1\" y=\"1\" z=\"-1\"/><vertex x=\"-1\" y=\"-1\" z=\"1\"/>\n"
    "  </vertices><triangles>\n"
    "   <triangle v1=\"0\" v2=\"1\" v3=\"2\"/><triangle v1=\"0\" v2=\"3\" v3=\"1\"/>\n"
    "   <triangle v1=\"0\" v2=\"2\" v3=\"3\"/><triangle v1=\"1\" v2=\"3\" v3=\"2\"/>\n"
    "  </triangles></mesh></object>\n";

TEST_F(MeshFormats, ThreeMfPlacesItemsAndComponentsInMillimetres) {
    // Object 2 is object 1 moved by +3 in x; the build places object 2 as it is and object 1
    // mirrored in x, all in centimetres.
    const std::string model =
        std::string(
            "<?xml version=\"1.0\"?>\n<!-- a comment <object> -->\n"
            "<model unit=\"centimeter\" xmlns=\"http://schemas.microsoft.com/"
            "3dmanufacturing/core/2015/02\">\n <resources>\n") +
        kTetObject +
        "  <object id=\"2\"><components><component objectid=\"1\" "
        "transform=\"1 0 0 0 1 0 0 0 1 3 0 0\"/></components></object>\n"
        " </resources>\n <build><item objectid=\"2\"/>"
        "<item objectid=\"1\" transform=\"-1 0 0 0 1 0 0 0 1 0 0 0\"/></build>\n</model>\n";
    const io::MeshReadResult r = io::readMesh(packageOf(dir_ / "p.3mf", model));
    ASSERT_TRUE(r.mesh) << r.error;
    ASSERT_EQ(r.mesh->triangles.size(), 8u);
    // Two tetrahedra of edge 2 cm, disjoint: each 8/3 cm^3 = 8000/3 mm^3, both outward.
    EXPECT_NEAR(csg::signedVolume(*r.mesh), 2 * 8000.0 / 3.0, 1e-9);
    EXPECT_TRUE(csg::checkTopology(*r.mesh).closedManifold());
    double lo = 1e9, hi = -1e9;
    for (const csg::Vec3& p : r.mesh->positions) {
        lo = std::min(lo, p.x);
        hi = std::max(hi, p.x);
    }
    EXPECT_EQ(lo, -10.0);  // the mirrored one: x in [-10, 10] mm
    EXPECT_EQ(hi, 40.0);   // the moved one: x in [20, 40] mm
}

TEST_F(MeshFormats, BrokenThreeMfSaysWhereInTheModelPart) {
    struct Case {
        const char* name;
        std::string model;
        const char* message;
        uint32_t line;
    };
    const std::string head = "<model unit=\"millimeter\">\n<resources>\n";
    const Case cases[] = {
        {"index",
         head + "<object id=\"1\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/>\n"
                "</vertices><triangles>\n<triangle v1=\"0\" v2=\"0\" v3=\"1\"/>\n",
         "v3 names no vertex", 5},
        {"number", head + "<object id=\"1\"><mesh><vertices>\n<vertex x=\"0\" y=\"nan\" z=\"0\"/>",
         "a vertex needs a finite number y", 4},
        {"unit", "<model unit=\"parsec\">", "unknown unit 'parsec'", 1},
        {"cycle",
         head + "<object id=\"1\"><components><component objectid=\"1\"/></components>"
                "</object></resources>\n<build><item objectid=\"1\"/></build></model>",
         "(a cycle?)", 4},
        {"missing", head + "</resources>\n<build>\n<item objectid=\"9\"/></build></model>",
         "object 9 is not defined", 5},
        {"tag", head + "<object id=\"1\" name=\"x>", "not closed", 3},
    };
    for (const Case& c : cases) {
        const io::MeshReadResult r =
            io::readMesh(packageOf(dir_ / (std::string(c.name) + ".3mf"), c.model));
        EXPECT_FALSE(r.mesh) << c.name;
        EXPECT_NE(r.error.find(c.message), std::string::npos) << c.name << ": " << r.error;
        EXPECT_NE(r.error.find("3D/3dmodel.model"), std::string::npos) << c.name << ": " << r.error;
        EXPECT_EQ(r.line, c.line) << c.name << ": " << r.error;
    }
    writeFile(dir_ / "notzip.3mf", "solid x\nendsolid x\n");
    EXPECT_NE(io::readMesh(dir_ / "notzip.3mf").error.find("not a readable zip"),
              std::string::npos);
}

}  // namespace
