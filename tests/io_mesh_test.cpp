// Reading mesh files for compare (io/mesh/MeshFile.h): OBJ and STL (binary and ASCII) into a welded
// triangle soup, in time linear in the file whatever the valences, keeping non-manifold faces
// for compare to report, errors with the line and column of the text formats, and malformed
// glTF and unmeasurable coordinates refused with their reason.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "csg/mesh/MeshCheck.h"
#include "io/mesh/MeshFile.h"

namespace {

namespace fs = std::filesystem;

// A file under a fresh temporary directory, removed with it.
class MeshFiles : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ =
            fs::temp_directory_path() /
            ("io_mesh_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path write(const std::string& name, const std::string& bytes) {
        const fs::path path = dir_ / name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    }
    fs::path dir_;
};

// A binary STL of the given triangles (little-endian floats, zero normals).
std::string binaryStl(const std::vector<std::array<csg::Vec3, 3>>& triangles) {
    std::string bytes(80, ' ');
    auto put32 = [&](uint32_t u) {
        for (int i = 0; i < 4; ++i) bytes.push_back(char(u >> (8 * i) & 0xff));
    };
    auto putFloat = [&](double d) {
        const float f = float(d);
        uint32_t u;
        std::memcpy(&u, &f, 4);
        put32(u);
    };
    put32(uint32_t(triangles.size()));
    for (const auto& t : triangles) {
        for (int k = 0; k < 3; ++k) putFloat(0.0);
        for (const csg::Vec3& p : t)
            for (int k = 0; k < 3; ++k) putFloat(p[k]);
        bytes += std::string(2, '\0');
    }
    return bytes;
}

// The regular tetrahedron's corners and outward triangles.
const csg::Vec3 kTet[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
const int kTetFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};

// The tetrahedron as OBJ text, its faces outward.
std::string tetObj() {
    std::string obj = "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\n";
    for (const auto& f : kTetFaces)
        obj += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " +
               std::to_string(f[2] + 1) + "\n";
    return obj;
}

std::vector<std::array<csg::Vec3, 3>> tetTriangles() {
    std::vector<std::array<csg::Vec3, 3>> out;
    for (const auto& f : kTetFaces) out.push_back({kTet[f[0]], kTet[f[1]], kTet[f[2]]});
    return out;
}

TEST_F(MeshFiles, BinaryAndAsciiStlWeldToTheSameClosedTetrahedron) {
    std::string ascii = "solid tet\n";
    for (const auto& t : tetTriangles()) {
        ascii += "  facet normal 0 0 0\n    outer loop\n";
        for (const csg::Vec3& p : t)
            ascii += "      vertex " + std::to_string(int(p.x)) + " " + std::to_string(int(p.y)) +
                     " " + std::to_string(int(p.z)) + "\n";
        ascii += "    endloop\n  endfacet\n";
    }
    ascii += "endsolid tet\n";
    // A binary header that starts with "solid", as several exporters write it: the size
    // decides.
    std::string binary = binaryStl(tetTriangles());
    binary.replace(0, 5, "solid");
    for (const fs::path& file : {write("a.stl", ascii), write("b.stl", binary)}) {
        const io::MeshReadResult r = io::readMesh(file);
        ASSERT_TRUE(r.mesh) << file << ": " << r.error;
        EXPECT_EQ(r.mesh->positions.size(), 4u) << file;
        ASSERT_EQ(r.mesh->triangles.size(), 4u) << file;
        for (int t = 0; t < 4; ++t)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(r.mesh->positions[r.mesh->triangles[size_t(t)][size_t(c)]],
                          kTet[kTetFaces[t][c]])
                    << file;
        EXPECT_TRUE(csg::checkTopology(*r.mesh).closedManifold()) << file;
        EXPECT_NEAR(csg::signedVolume(*r.mesh), 8.0 / 3.0, 1e-12) << file;
    }
}

TEST_F(MeshFiles, ObjFacesTakeEveryCornerFormAndNegativeIndices) {
    // A unit cube: quads (fans from their first corner), v/vt/vn, v//vn and v/vt corners,
    // negative (relative) indices, and statements compare does not need.
    const std::string obj =
        "# cube\nmtllib none.mtl\no cube\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1 1.0\nv 0 1 1\n"
        "vt 0 0\nvn 0 0 1\ns off\nusemtl x\n"
        "f 1/1/1 4/1/1 3/1/1 2/1/1\n"
        "f 5//1 6//1 7//1 8//1\r\n"
        "f 1/1 2/1 6/1 5/1\n"
        "f\t2 3 7 6\n"
        "f -6 -5 -1 -2\n"  // 3 4 8 7
        "f 4 1 5 8  \n";
    const io::MeshReadResult r = io::readMesh(write("cube.obj", obj));
    ASSERT_TRUE(r.mesh) << r.error;
    EXPECT_EQ(r.mesh->positions.size(), 8u);
    ASSERT_EQ(r.mesh->triangles.size(), 12u);
    EXPECT_EQ(r.mesh->triangles[0], (std::array<uint32_t, 3>{0, 3, 2}));
    EXPECT_EQ(r.mesh->triangles[1], (std::array<uint32_t, 3>{0, 2, 1}));
    EXPECT_EQ(r.mesh->triangles[8], (std::array<uint32_t, 3>{2, 3, 7}));
    EXPECT_TRUE(csg::checkTopology(*r.mesh).closedManifold());
    EXPECT_NEAR(csg::signedVolume(*r.mesh), 1.0, 1e-15);
}

TEST_F(MeshFiles, ObjLineContinuationsJoinLines) {
    // The same unit cube with statements split by a backslash at a line's end (after a blank,
    // right after an index, before a CRLF); a backslash elsewhere is not a continuation.
    const std::string obj =
        "v 0 0 0\nv 1 \\\n 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 \\\n 3 2\n"
        "f 5 6\\\r\n7 8\n"
        "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    const io::MeshReadResult r = io::readMesh(write("continued.obj", obj));
    ASSERT_TRUE(r.mesh) << r.error;
    EXPECT_EQ(r.mesh->positions.size(), 8u);
    ASSERT_EQ(r.mesh->triangles.size(), 12u);
    EXPECT_EQ(r.mesh->triangles[2], (std::array<uint32_t, 3>{4, 5, 6}));
    EXPECT_TRUE(csg::checkTopology(*r.mesh).closedManifold());
    EXPECT_NEAR(csg::signedVolume(*r.mesh), 1.0, 1e-15);

    // An error on a continued line names that line and its column.
    const io::MeshReadResult bad =
        io::readMesh(write("badcont.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n  2 x\n"));
    EXPECT_FALSE(bad.mesh);
    EXPECT_EQ(bad.line, 5u);
    EXPECT_EQ(bad.column, 5u);
    const io::MeshReadResult stray =
        io::readMesh(write("stray.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\\ 3\n"));
    EXPECT_FALSE(stray.mesh);
    EXPECT_EQ(stray.line, 4u);
    EXPECT_EQ(stray.column, 6u);
}

TEST_F(MeshFiles, NonManifoldFacesAreKeptForCompareToReport) {
    // The tetrahedron with one face written three times: OpenMesh's half-edge structure
    // refused the copies, so compare saw a closed mesh.
    std::string obj = tetObj();
    obj += "f 1 2 3\nf 1 3 2\nf 1 1 2\n";
    const io::MeshReadResult r = io::readMesh(write("doubled.obj", obj));
    ASSERT_TRUE(r.mesh) << r.error;
    EXPECT_EQ(r.mesh->triangles.size(), 7u);
    const csg::MeshTopology topo = csg::checkTopology(*r.mesh);
    EXPECT_FALSE(topo.closedManifold());
    EXPECT_EQ(topo.nonManifoldEdges, 3u);
    EXPECT_EQ(topo.degenerateTriangles, 1u);
}

// A face written a second time both ways round is a fin of no volume folded onto the
// tetrahedron, not two solids touching: its edges keep four triangles each for compare to
// report (the wedges between them are empty, tol::kTouchingSheetsMinWedge), where two cubes
// that meet along an edge are told apart (exact_mesh_test).
TEST_F(MeshFiles, AFaceFoldedOntoAnotherIsNotTakenForTouchingSheets) {
    std::string obj = tetObj();
    obj += "f 1 2 3\nf 1 3 2\n";
    const io::MeshReadResult r = io::readMesh(write("fin.obj", obj));
    ASSERT_TRUE(r.mesh) << r.error;
    EXPECT_EQ(r.mesh->positions.size(), 4u);
    const csg::MeshTopology topo = csg::checkTopology(*r.mesh);
    EXPECT_FALSE(topo.closedManifold());
    EXPECT_EQ(topo.nonManifoldEdges, 3u);
}

// One vertex of valence 100,000 (a cone's apex, and its base's centre): OpenMesh's reader
// searched the half-edges around a vertex for every face added there, ~20 s for this file.
TEST_F(MeshFiles, HighValenceStlLoadsInLinearTime) {
    constexpr int kSides = 100000;
    std::vector<std::array<csg::Vec3, 3>> triangles;
    const csg::Vec3 apex(0, 0, 1), centre(0, 0, 0);
    auto rim = [](int i) {
        const double a = 2.0 * M_PI * (i % kSides) / kSides;
        return csg::Vec3(float(std::cos(a)), float(std::sin(a)), 0.0);
    };
    for (int i = 0; i < kSides; ++i) {
        triangles.push_back({apex, rim(i), rim(i + 1)});
        triangles.push_back({centre, rim(i + 1), rim(i)});
    }
    const fs::path file = write("cone.stl", binaryStl(triangles));
    const auto start = std::chrono::steady_clock::now();
    const io::MeshReadResult r = io::readMesh(file);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(r.mesh) << r.error;
    EXPECT_EQ(r.mesh->positions.size(), size_t(kSides + 2));
    EXPECT_EQ(r.mesh->triangles.size(), size_t(2 * kSides));
    const csg::MeshTopology topo = csg::checkTopology(*r.mesh);
    EXPECT_TRUE(topo.closedManifold());
    EXPECT_EQ(topo.edges, size_t(3 * kSides));
    // A guard against the quadratic reader (~20 s), not a speed figure: the whole test took
    // 0.57 s on the shared 2-core machine at load 5 (~0.1 s read unloaded), so 5 s is ten
    // times a loaded run and a quarter of the quadratic one.
    EXPECT_LT(seconds, 5.0);
}

struct BadFile {
    const char* name;
    const char* text;
    uint32_t line, column;
    const char* message;  // a part of the error
};

TEST_F(MeshFiles, ErrorsInTextFilesSayWhere) {
    const BadFile cases[] = {
        {"number.obj", "v 0 0 0\nv 1 x 0\n", 2, 5, "expected a finite number"},
        {"short.obj", "v 0 0 0\nv 1 0 0\n", 0, 0, ""},  // no faces: an empty mesh, no error
        {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, 7, "index 4 names no vertex"},
        {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf  0 2 3\n", 5, 4, "index 0 names no vertex"},
        {"back.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4, 7, "index -4"},
        {"two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", 3, 1, "at least 3"},
        {"junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2.5 3\n", 4, 6, "expected a vertex index"},
        {"inf.obj", "v 0 inf 0\n", 1, 5, "finite"},
        {"huge.obj", "v 0 0 0\nv 0 -2e30 0\n", 2, 5, "cannot be measured"},
        {"loop.stl",
         "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
         "   vertex 1 0 0\n  endloop\n endfacet\nendsolid x\n",
         6, 3, "at least 3"},
        {"word.stl", "solid x\n facet normal 0 0 1\n  outer lop\n", 3, 9, "expected 'outer loop'"},
        {"num.stl",
         "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
         "   vertex 1 0 0\n   vertex 0 1 z\n",
         6, 15, "expected a finite number"},
        {"huge.stl",
         "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1e31 0 0\n", 5, 11,
         "cannot be measured"},
        {"normal.stl", "solid x\n facet normal 0 0\n  outer loop\n", 2, 18, "expected 3 numbers"},
        // Normals are not used, so the "nan" some writers put there is skipped.
        {"nan_normal.stl",
         "solid x\n facet normal nan nan nan\n  outer loop\n   vertex 0 0 0\n"
         "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid x\n",
         0, 0, ""},
    };
    for (const BadFile& c : cases) {
        const io::MeshReadResult r = io::readMesh(write(c.name, c.text));
        if (*c.message == '\0') {
            EXPECT_TRUE(r.mesh) << c.name << ": " << r.error;
            continue;
        }
        EXPECT_FALSE(r.mesh) << c.name;
        EXPECT_FALSE(r.unreadable) << c.name;
        EXPECT_NE(r.error.find(c.message), std::string::npos) << c.name << ": " << r.error;
        EXPECT_EQ(r.line, c.line) << c.name << ": " << r.error;
        EXPECT_EQ(r.column, c.column) << c.name << ": " << r.error;
    }
}

TEST_F(MeshFiles, BrokenBinaryStlAndMissingFiles) {
    std::string binary = binaryStl(tetTriangles());
    binary.pop_back();
    const io::MeshReadResult cut = io::readMesh(write("cut.stl", binary));
    EXPECT_FALSE(cut.mesh);
    EXPECT_NE(cut.error.find("the header says 4 facets (284 bytes), the file has 283"),
              std::string::npos)
        << cut.error;
    const io::MeshReadResult tiny = io::readMesh(write("tiny.stl", "abc"));
    EXPECT_FALSE(tiny.mesh);
    EXPECT_FALSE(tiny.error.empty());
    std::string nan = binaryStl(tetTriangles());
    nan.replace(84 + 50 + 12 + 4, 4, "\0\0\xc0\x7f", 4);  // facet 2, corner 1's y: a NaN
    const io::MeshReadResult bad = io::readMesh(write("nan.stl", nan));
    EXPECT_FALSE(bad.mesh);
    EXPECT_NE(bad.error.find("facet 2"), std::string::npos) << bad.error;
    for (const char* missing : {"none.obj", "none.stl"}) {
        const io::MeshReadResult r = io::readMesh(dir_ / missing);
        EXPECT_FALSE(r.mesh);
        EXPECT_TRUE(r.unreadable) << missing;
    }
}

// A glTF of one triangle (POSITION floats, then uint16 indices in one data-URI buffer of 44
// bytes), with the accessors and nodes given; indices2 is the third index.
std::string gltfTriangle(const std::string& accessors, const std::string& nodes, int indices2 = 2) {
    const std::string buffer = indices2 == 2
                                   ? "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="
                                   : "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAMAAAA=";
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
           R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
           R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)" +
           buffer +
           R"("}],"bufferViews":[{"buffer":0,"byteLength":36},)"
           R"({"buffer":0,"byteOffset":36,"byteLength":8}],"accessors":)" +
           accessors + "}";
}

TEST_F(MeshFiles, MalformedGltfIsRefusedWithItsReason) {
    const std::string position = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";
    const std::string indices =
        R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"})";
    const std::string good = "[" + position + "," + indices + "]";
    const std::string oneNode = R"([{"mesh":0}])";
    const io::MeshReadResult r = io::readMesh(write("good.gltf", gltfTriangle(good, oneNode)));
    ASSERT_TRUE(r.mesh) << r.error;  // the file the cases below each break in one place
    EXPECT_EQ(r.mesh->positions.size(), 3u);
    EXPECT_EQ(r.mesh->triangles.size(), 1u);

    struct Case {
        const char* name;
        std::string gltf;
        const char* message;  // a part of the error
    };
    const Case cases[] = {
        {"count",
         gltfTriangle("[" + std::string(R"({"bufferView":0,"componentType":5126,)") +
                          R"("count":1099511627776,"type":"VEC3"},)" + indices + "]",
                      oneNode),
         "reaching past its buffer"},
        {"matrix",
         gltfTriangle(good, R"([{"mesh":0,"matrix":[1e300,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}])"),
         "cannot be measured"},
        // Node 0's children name node 1 twice: nodes must form trees.
        {"shared", gltfTriangle(good, R"([{"children":[1,1]},{"mesh":0}])"), "reached twice"},
        {"float_indices",
         gltfTriangle("[" + position +
                          R"(,{"bufferView":1,"componentType":5126,"count":2,"type":"SCALAR"}])",
                      oneNode),
         "not unsigned integer"},
        {"index", gltfTriangle(good, oneNode, 3), "past the primitive's vertices"},
    };
    for (const Case& c : cases) {
        const io::MeshReadResult bad = io::readMesh(write(std::string(c.name) + ".gltf", c.gltf));
        EXPECT_FALSE(bad.mesh) << c.name;
        EXPECT_NE(bad.error.find(c.message), std::string::npos) << c.name << ": " << bad.error;
    }
}

}  // namespace
