// End-to-end tests of `csgray export` and `csgray compare`: every sample exports to a GLB that
// the Khronos glTF validator accepts without errors or warnings and that compare finds within
// the tolerance, closed, outward and free of self-intersections; OBJ and glTF round trips; the
// empty part; exit codes.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "CliRunner.h"
#include "MissingTool.h"

namespace cli {
namespace {

// The validator's report for a file, or nothing (with why) when node or the npm package is
// missing (a skip) or the validator failed (a test failure); the package is installed by
// `cmake --build BUILD --target gltf_validator`.
std::optional<nlohmann::json> validate(const fs::path& file, std::string& why) {
    const fs::path modules = GLTF_VALIDATOR_DIR;
    if (std::system("node --version >/dev/null 2>&1") != 0) {
        why = "node is not installed";
        return std::nullopt;
    }
    if (!fs::exists(modules / "gltf-validator")) {
        why = "gltf-validator is not installed in " + modules.string() +
              " (cmake --build <build> --target gltf_validator)";
        return std::nullopt;
    }
    const fs::path out = file.parent_path() / ".validator";
    const std::string command = "node " + shellQuote(GLTF_VALIDATE_JS) + " " +
                                shellQuote(modules.string()) + " " + shellQuote(file.string()) +
                                " >" + shellQuote(out.string()) + " 2>&1";
    const int status = std::system(command.c_str());
    const std::string text = readFile(out);
    if (status != 0) {
        // node and the package are there, so a run that fails (an unreadable or malformed
        // file the validator throws on) is a failure of the test, not a reason to skip it.
        ADD_FAILURE() << "glTF validator failed on " << file << ": " << text;
        why = "validator failed: " + text;
        return std::nullopt;
    }
    return nlohmann::json::parse(text);
}

// Expects the validator to report no errors and no warnings on a file; false (with why) when
// there is no report (validator missing: the caller may skip, except in CI, where the install
// script was to bring it and its absence is a failure here; validator failed: already a
// failure).
bool validatorAccepts(const fs::path& file, std::string& why) {
    const std::optional<nlohmann::json> report = validate(file, why);
    if (!report) {
        if (csg::testing::inCi()) ADD_FAILURE() << "in CI a missing tool fails: " << why;
        return false;
    }
    EXPECT_EQ((*report)["errors"].get<int>(), 0) << report->dump();
    EXPECT_EQ((*report)["warnings"].get<int>(), 0) << report->dump();
    return true;
}

// A tolerance of 1/60 of the part's bounding-box diagonal, from `csgray info`.
double toleranceOf(const fs::path& part, const fs::path& dir) {
    const RunResult info = runCsgray({"info", part.string()}, dir);
    const nlohmann::json j = nlohmann::json::parse(info.out);
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double e = j["bounds"]["max"][a].get<double>() - j["bounds"]["min"][a].get<double>();
        d2 += e * e;
    }
    return std::sqrt(d2) / 60.0;
}

TEST(CliMesh, EverySampleExportsToAValidGlbWithinTolerance) {
    ScratchDir dir;
    int count = 0;
    for (const auto& entry : fs::directory_iterator(CSGRAY_SAMPLES)) {
        if (entry.path().extension() != ".scad") continue;
        SCOPED_TRACE(entry.path().filename().string());
        const std::string tol = std::to_string(toleranceOf(entry.path(), dir.path()));
        const fs::path glb = dir.path() / (entry.path().stem().string() + ".glb");
        const RunResult e = runCsgray({"export", entry.path().string(), "-o", glb.string(),
                                       "--tolerance", tol, "--max-cells", "2000000"},
                                      dir.path());
        // A surface (a patch set with solid=false, e.g. teapot.scad) has no volume: export
        // refuses it by design (viewer/cli/LoadPart.h, requireSolids).
        if (e.exitCode == 1 && e.err.find("solid=false") != std::string::npos) continue;
        ASSERT_EQ(e.exitCode, 0) << e.err;
        const RunResult c = runCsgray({"compare", entry.path().string(), glb.string(), "--json",
                                       "--tolerance", tol, "--samples", "128"},
                                      dir.path());
        const nlohmann::json j = nlohmann::json::parse(c.out);
        // table's legs touch its apron along an edge (a non-manifold solid): the mesh is
        // manifold by its indices (mesh_test checks that), but after rounding to float and
        // welding equal positions, a few vertices on that edge coincide.
        const bool touching = entry.path().filename() == "table.scad";
        if (!touching) {
            EXPECT_TRUE(j["topology"]["closedManifold"].get<bool>()) << c.out;
        }
        EXPECT_TRUE(j["topology"]["outward"].get<bool>()) << c.out;
        // Issue 7 promises no self-intersections, and these meshes are simplified (mesh_test
        // holds the grid's meshes to it): at this tolerance simplification made crossings in
        // csg_grid (2 pairs) and dice (16) before collapses were checked for them.
        EXPECT_EQ(j["topology"]["selfIntersections"].get<uint64_t>(), 0u) << c.out;
        EXPECT_LE(j["meshToSurface"]["max"].get<double>(), std::stod(tol)) << c.out;
        if (!touching) {
            EXPECT_EQ(c.exitCode, 0) << c.out;
        }
        // csg_grid ($fn = 64: every leaf a polyhedron) gets its exact boundary: its
        // interpenetrating neighbours' wedge gaps, which the grid fused at their tips, are
        // kept to the last one, and no grid warning is left to give.
        if (entry.path().filename() == "csg_grid.scad") {
            EXPECT_NE(e.err.find("exact polyhedral boundary"), std::string::npos) << e.err;
            EXPECT_EQ(e.err.find("thinner than the cell"), std::string::npos) << e.err;
        }
        std::string why;
        if (!validatorAccepts(glb, why) && count == 0) {
            std::printf("glTF validation skipped: %s\n", why.c_str());
        }
        ++count;
    }
    EXPECT_GE(count, 10);
}

TEST(CliMesh, GlbPassesTheKhronosValidator) {
    ScratchDir dir;
    const fs::path glb = dir.path() / "pawn.glb";
    ASSERT_EQ(
        runCsgray({"export", samplePath("pawn.scad").string(), "-o", glb.string()}, dir.path())
            .exitCode,
        0);
    std::string why;
    if (!validatorAccepts(glb, why)) SKIP_OR_FAIL_IN_CI(why);
}

// An all-polyhedral part exports its exact boundary, which the validator accepts like any
// GLB; --grid meshes the same part on the grid (its summary names the cell).
TEST(CliMesh, ExactPolyhedralExportAndTheGridFlag) {
    ScratchDir dir;
    const fs::path part = dir.path() / "notched.scad";
    std::ofstream(part) << "difference() { cube(2, center=true); cube(1); }\n";
    const fs::path glb = dir.path() / "notched.glb";
    const RunResult exact = runCsgray({"export", part.string(), "-o", glb.string()}, dir.path());
    ASSERT_EQ(exact.exitCode, 0) << exact.err;
    EXPECT_NE(exact.err.find("the exact polyhedral boundary"), std::string::npos) << exact.err;
    const RunResult c = runCsgray({"compare", part.string(), glb.string(), "--json"}, dir.path());
    const nlohmann::json j = nlohmann::json::parse(c.out);
    EXPECT_NEAR(j["volume"]["mesh"].get<double>(), 7.0, 1e-6) << c.out;  // 8 - 1, in floats
    EXPECT_TRUE(j["topology"]["closedManifold"].get<bool>()) << c.out;

    const fs::path gridGlb = dir.path() / "grid.glb";
    const RunResult grid =
        runCsgray({"export", part.string(), "-o", gridGlb.string(), "--grid"}, dir.path());
    ASSERT_EQ(grid.exitCode, 0) << grid.err;
    EXPECT_EQ(grid.err.find("exact polyhedral boundary"), std::string::npos) << grid.err;
    EXPECT_NE(grid.err.find("cell"), std::string::npos) << grid.err;

    std::string why;
    if (!validatorAccepts(glb, why)) SKIP_OR_FAIL_IN_CI(why);
}

TEST(CliMesh, ObjAndGltfRoundTrip) {
    ScratchDir dir;
    const std::string part = samplePath("bracket.scad").string();
    for (const char* name : {"b.obj", "b.gltf"}) {
        SCOPED_TRACE(name);
        const fs::path out = dir.path() / name;
        const RunResult e =
            runCsgray({"export", part, "-o", out.string(), "--tolerance", "0.2"}, dir.path());
        ASSERT_EQ(e.exitCode, 0) << e.err;
        const RunResult c = runCsgray(
            {"compare", part, out.string(), "--tolerance", "0.2", "--samples", "128"}, dir.path());
        EXPECT_EQ(c.exitCode, 0) << c.out << c.err;
        EXPECT_NE(c.out.find("closed manifold, outward"), std::string::npos) << c.out;
    }
    std::string why;
    validatorAccepts(dir.path() / "b.gltf", why);  // skipped (why) without the validator
}

// The triangles of an ASCII STL (its facets), as OpenSCAD writes it.
size_t asciiStlFacets(const fs::path& stl) {
    const std::string text = readFile(stl);
    size_t n = 0;
    for (size_t at = text.find("facet normal"); at != std::string::npos;
         at = text.find("facet normal", at + 1))
        ++n;
    return n;
}

// The triangle count `csgray export` reports on stderr ("FILE: N triangles").
size_t exportedTriangles(const std::string& err) {
    const size_t at = err.find(" triangles");
    if (at == std::string::npos) return 0;
    const size_t start = err.rfind(' ', at - 1) + 1;
    return size_t(std::stoull(err.substr(start, at - start)));
}

TEST(CliMesh, StlAnd3mfExportsCompareAndOpenScadReadsThem) {
    ScratchDir dir;
    const std::string part = samplePath("bracket.scad").string();
    const std::vector<std::vector<std::string>> exports = {
        {"b.stl"}, {"a.stl", "--ascii"}, {"b.3mf"}};
    size_t triangles = 0;
    for (const auto& e : exports) {
        SCOPED_TRACE(e[0]);
        const fs::path out = dir.path() / e[0];
        std::vector<std::string> args = {"export", part, "-o", out.string(), "--tolerance", "0.2"};
        args.insert(args.end(), e.begin() + 1, e.end());
        const RunResult r = runCsgray(args, dir.path());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        triangles = exportedTriangles(r.err);
        ASSERT_GT(triangles, 0u) << r.err;
        const RunResult c = runCsgray(
            {"compare", part, out.string(), "--tolerance", "0.2", "--samples", "128"}, dir.path());
        EXPECT_EQ(c.exitCode, 0) << c.out << c.err;
        EXPECT_NE(c.out.find("closed manifold, outward"), std::string::npos) << c.out;
    }
    EXPECT_EQ(readFile(dir.path() / "a.stl").rfind("solid", 0), 0u);
    EXPECT_EQ(readFile(dir.path() / "b.stl").size(), 84 + 50 * triangles);
    EXPECT_EQ(runCsgray({"export", part, "-o", "x.glb", "--ascii"}, dir.path()).exitCode, 2);

    if (std::system("openscad --version >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad is not installed");
    // OpenSCAD imports each file (its own STL and 3MF readers, lib3mf for 3MF) and writes the
    // same triangles back, within the tolerance of the part.
    for (const auto& e : exports) {
        SCOPED_TRACE(e[0]);
        const fs::path scad = dir.path() / ("import_" + e[0] + ".scad");
        const fs::path back = dir.path() / ("openscad_" + e[0] + ".stl");
        writeFile(scad, "import(\"" + (dir.path() / e[0]).string() + "\");\n");
        const std::string command = "openscad -o " + shellQuote(back.string()) + " " +
                                    shellQuote(scad.string()) + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        EXPECT_EQ(asciiStlFacets(back), triangles);
        const RunResult c = runCsgray(
            {"compare", part, back.string(), "--tolerance", "0.2", "--samples", "128"}, dir.path());
        EXPECT_EQ(c.exitCode, 0) << c.out << c.err;
    }
    // csgray reads OpenSCAD's 3MF (lib3mf's ZIP64 package) as the same mesh as its STL.
    double volume[2];
    const char* names[2] = {"openscad.3mf", "openscad.stl"};
    for (int i = 0; i < 2; ++i) {
        const fs::path out = dir.path() / names[i];
        const std::string command =
            "openscad -o " + shellQuote(out.string()) + " " + shellQuote(part) + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const RunResult c = runCsgray(
            {"compare", part, out.string(), "--json", "--samples", "64", "--tolerance", "1"},
            dir.path());
        ASSERT_FALSE(c.out.empty()) << c.err;
        const nlohmann::json j = nlohmann::json::parse(c.out);
        EXPECT_TRUE(j["topology"]["closedManifold"].get<bool>()) << names[i] << c.out;
        volume[i] = j["volume"]["mesh"].get<double>();
    }
    // OpenSCAD writes STL coordinates to 6 significant digits (11.7634) and 3MF ones to 6
    // decimals: the two volumes differ by that rounding, well below 1e-5 of the part's.
    EXPECT_NEAR(volume[0], volume[1], 1e-5 * volume[1]);
}

TEST(CliMesh, EmptyPartGivesAValidEmptyFileAndAWarning) {
    ScratchDir dir;
    const fs::path part = dir.path() / "empty.scad";
    writeFile(part, "difference() { cube(1); cube(3, center = true); }\n");
    for (const char* name : {"e.glb", "e.obj", "e.gltf", "e.stl", "e.3mf"}) {
        const fs::path out = dir.path() / name;
        const RunResult r = runCsgray({"export", part.string(), "-o", out.string()}, dir.path());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
        EXPECT_TRUE(fs::exists(out));
    }
    std::string why;
    validatorAccepts(dir.path() / "e.glb", why);  // skipped (why) without the validator
}

TEST(CliMesh, ExitCodes) {
    ScratchDir dir;
    const std::string part = samplePath("pawn.scad").string();
    // Usage: no -o, an unknown extension, a bad tolerance, compare without a mesh.
    EXPECT_EQ(runCsgray({"export", part}, dir.path()).exitCode, 2);
    EXPECT_EQ(runCsgray({"export", part, "-o", "x.ply"}, dir.path()).exitCode, 2);
    EXPECT_EQ(runCsgray({"export", part, "-o", "x.glb", "--tolerance", "-1"}, dir.path()).exitCode,
              2);
    EXPECT_EQ(runCsgray({"compare", part}, dir.path()).exitCode, 2);
    // I/O: an output directory that does not exist (and nothing left behind), a missing mesh.
    const fs::path missing = dir.path() / "no" / "such" / "x.glb";
    EXPECT_EQ(runCsgray({"export", part, "-o", missing.string()}, dir.path()).exitCode, 3);
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_EQ(runCsgray({"compare", part, (dir.path() / "none.obj").string()}, dir.path()).exitCode,
              3);
    EXPECT_EQ(runCsgray({"export", (dir.path() / "none.scad").string(), "-o", "x.glb"}, dir.path())
                  .exitCode,
              3);
    // A malformed mesh: a bad model (1) and the error where it is in the file.
    writeFile(dir.path() / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    const RunResult bad =
        runCsgray({"compare", part, (dir.path() / "bad.obj").string()}, dir.path());
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("bad.obj:4:7: error: vertex index 7 names no vertex"), std::string::npos)
        << bad.err;
}

TEST(CliMesh, CompareFindsAWrongMeshAndAHole) {
    ScratchDir dir;
    const fs::path part = dir.path() / "cube.scad";
    writeFile(part, "cube(10);\n");
    // The right cube, then one 0.5 too tall, then the right one with a face missing.
    const std::string vertices =
        "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 H\nv 10 0 H\nv 10 10 H\nv 0 10 H\n";
    const std::string faces = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    auto cube = [&](const std::string& h, const std::string& f) {
        std::string v = vertices;
        for (size_t p; (p = v.find('H')) != std::string::npos;) v.replace(p, 1, h);
        return v + f;
    };
    writeFile(dir.path() / "good.obj", cube("10", faces));
    writeFile(dir.path() / "tall.obj", cube("10.5", faces));
    writeFile(dir.path() / "open.obj", cube("10", faces.substr(0, faces.rfind("f 4"))));
    auto compare = [&](const char* mesh) {
        return runCsgray({"compare", part.string(), (dir.path() / mesh).string(), "--json",
                          "--tolerance", "0.1"},
                         dir.path());
    };
    // The right cube and a small one through its top face (z = 10) at x, y in [2, 4].
    std::string pierced = cube("10", faces) +
                          "v 2 2 8\nv 4 2 8\nv 4 4 8\nv 2 4 8\nv 2 2 12\nv 4 2 12\nv 4 4 12\n"
                          "v 2 4 12\n";
    for (const char* f : {"f 9 12 11 10\n", "f 13 14 15 16\n", "f 9 10 14 13\n", "f 10 11 15 14\n",
                          "f 11 12 16 15\n", "f 12 9 13 16\n"})
        pierced += f;
    writeFile(dir.path() / "pierced.obj", pierced);
    const RunResult good = compare("good.obj");
    EXPECT_EQ(good.exitCode, 0) << good.out << good.err;
    EXPECT_EQ(nlohmann::json::parse(good.out)["topology"]["selfIntersections"].get<uint64_t>(), 0u);
    const nlohmann::json p = nlohmann::json::parse(compare("pierced.obj").out);
    EXPECT_GT(p["topology"]["selfIntersections"].get<uint64_t>(), 0u) << p;
    EXPECT_EQ(p["topology"]["coplanarOverlaps"].get<uint64_t>(), 0u) << p;
    const auto at = p["topology"]["selfIntersectionAt"];
    EXPECT_NEAR(at[2].get<double>(), 10.0, 1e-9) << p;
    for (int a = 0; a < 2; ++a) {
        EXPECT_GE(at[a].get<double>(), 2.0 - 1e-9) << p;
        EXPECT_LE(at[a].get<double>(), 4.0 + 1e-9) << p;
    }
    const RunResult tall = compare("tall.obj");
    EXPECT_EQ(tall.exitCode, 1) << tall.out;
    EXPECT_NEAR(nlohmann::json::parse(tall.out)["meshToSurface"]["max"].get<double>(), 0.5, 1e-9);
    EXPECT_NEAR(nlohmann::json::parse(tall.out)["volume"]["mesh"].get<double>(), 1050.0, 1e-9);
    const RunResult open = compare("open.obj");
    EXPECT_EQ(open.exitCode, 1) << open.out;
    EXPECT_FALSE(nlohmann::json::parse(open.out)["topology"]["closedManifold"].get<bool>());
}

// OpenSCAD's number of fragments for a circle of radius r (Calc::get_fragments_from_r,
// OpenSCAD 2021.01) with $fn = 0 and the default $fa = 12, $fs = 2, as in pawn.scad.
int openScadFragments(double r) {
    constexpr double kFa = 12.0, kFs = 2.0;
    return int(std::ceil(std::max(std::min(360.0 / kFa, r * 2.0 * M_PI / kFs), 5.0)));
}

// OpenSCAD's own mesh of a sample, compared with the exact surface: its faceting error, bounded
// by what OpenSCAD's fragment rule implies for the sample's radii.
TEST(CliMesh, OpenScadStlCompares) {
    if (std::system("openscad --version >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad is not installed");
    // How far OpenSCAD's facets lie inside each of pawn.scad's primitives. Every vertex is on
    // the exact surface and each facet is a chord, so its deepest point is
    //  - cylinder(r1, r2): n = fragments(max(r1, r2)) sides; the widest side's chord has its
    //    middle max(r1, r2) (1 - cos(pi / n)) inside the circle;
    //  - sphere(r): n = fragments(r) around and rings = (n + 1) / 2 circles at polar angles
    //    180 (i + 1/2) / rings; the widest facet is the rectangle across the equator, whose
    //    plane is r cos(pi / n) cos(pi / (2 rings)) from the centre.
    // The union's facets are pieces of these, and a point of the mesh lies inside the exact
    // union within the depth of the facet it is on, so the largest depth bounds mesh->surface;
    // a point of the exact surface is no farther from the facet below it, which bounds
    // surface->mesh.
    auto cylinderDepth = [](double r1, double r2) {
        const double r = std::max(r1, r2);
        return r * (1.0 - std::cos(M_PI / openScadFragments(r)));
    };
    auto sphereDepth = [](double r) {
        const int n = openScadFragments(r), rings = (n + 1) / 2;
        return r * (1.0 - std::cos(M_PI / n) * std::cos(M_PI / (2 * rings)));
    };
    const double depth =
        std::max({cylinderDepth(10, 8), cylinderDepth(6, 3), cylinderDepth(5, 5), sphereDepth(5)});
    // The STL stores floats: coordinates up to ~26 are rounded by up to ~2e-6.
    const double bound = depth + 1e-5;

    ScratchDir dir;
    const fs::path stl = dir.path() / "pawn.stl";
    const std::string command = "openscad -o " + shellQuote(stl.string()) + " " +
                                shellQuote(samplePath("pawn.scad").string()) + " >/dev/null 2>&1";
    // OpenSCAD is installed (the test above checks): a failed export is a failure.
    ASSERT_TRUE(std::system(command.c_str()) == 0 && fs::exists(stl)) << command;
    // compare takes a sample's first line when it answers within --tolerance and tries more
    // lines (needed at the concave creases) only above it: half the bound keeps every sample
    // near the bound measured well.
    const RunResult c = runCsgray({"compare", samplePath("pawn.scad").string(), stl.string(),
                                   "--json", "--tolerance", std::to_string(depth / 2)},
                                  dir.path());
    ASSERT_FALSE(c.out.empty()) << c.err;
    const nlohmann::json j = nlohmann::json::parse(c.out);
    EXPECT_TRUE(j["topology"]["closedManifold"].get<bool>()) << c.out;
    const double meshToSurface = j["meshToSurface"]["max"].get<double>();
    const double surfaceToMesh = j["surfaceToMesh"]["max"].get<double>();
    EXPECT_LE(meshToSurface, bound) << c.out;
    EXPECT_LE(surfaceToMesh, bound) << c.out;
    // The bound is reached: the head's equator rectangles are split along a diagonal, whose
    // midpoint (a sample) is the rectangle's centre, the deepest point.
    EXPECT_GE(meshToSurface, 0.9 * depth) << c.out;
    std::printf("OpenSCAD pawn.stl: mesh->surface %g, surface->mesh %g (bound %g), volume %+.2e\n",
                meshToSurface, surfaceToMesh, depth,
                j["volume"]["relativeDifference"].get<double>());
}

}  // namespace
}  // namespace cli
