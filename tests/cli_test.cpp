// End-to-end tests of the csgray command line: exit codes (0 ok, 1 bad model or input,
// 2 usage, 3 I/O), diagnostics in both formats, no partial output file on failure, stdout
// carrying only the requested output, info's counts and bounds, and the rendered PNG decoded
// back with libpng.
#include <sys/resource.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>

#include "CliRunner.h"
#include "PngImage.h"

namespace cli {
namespace {

const std::string kEmblem = samplePath("emblem.scad").string();

// ---- help and usage ----

TEST(Help, TopLevelAndEverySubcommand) {
    ScratchDir dir;
    for (const std::vector<std::string>& args : {std::vector<std::string>{"--help"},
                                                 {"probe", "--help"},
                                                 {"info", "--help"},
                                                 {"render", "--help"},
                                                 {"probe", "-h"},
                                                 {"bench", "--help"},
                                                 {"bench", "accuracy", "-h"}}) {
        const RunResult r = runCsgray(args, dir.path());
        EXPECT_EQ(r.exitCode, 0) << args[0];
        EXPECT_NE(r.out.find("usage: csgray"), std::string::npos) << r.out;
        EXPECT_EQ(r.err, "");
    }
}

// csgray's heap is jemalloc on transparent huge pages (viewer/cli/HeapConfig.cpp): its statistics,
// printed at exit when asked through MALLOC_CONF (merged with the built-in configuration), show
// the options in force. glibc's malloc would ignore the variable and print nothing.
TEST(Heap, JemallocRunsWithTransparentHugePages) {
    ScratchDir dir;
    ASSERT_EQ(::setenv("MALLOC_CONF", "stats_print:true", 1), 0);
    const RunResult r = runCsgray({"--help"}, dir.path());
    ::unsetenv("MALLOC_CONF");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.err.find("opt.thp: \"always\""), std::string::npos) << r.err.substr(0, 2000);
    EXPECT_NE(r.err.find("opt.metadata_thp: \"auto\""), std::string::npos);
}

TEST(Usage, BadCommandLinesExitWithTwo) {
    ScratchDir dir;
    const std::vector<std::vector<std::string>> bad = {
        {},
        {"frobnicate"},
        {"probe", kEmblem},                                         // no ray
        {"probe", kEmblem, "--origin", "0,0", "--dir", "1,0,0"},    // two numbers
        {"probe", kEmblem, "--origin", "0,0,0", "--dir", "0,0,0"},  // zero direction
        {"probe", kEmblem, "--origin", "0,0,x", "--dir", "1,0,0"},
        {"probe", kEmblem, "--origin", "0,0,0", "--dir", "1,0,0", "--rays", "-"},
        {"probe", "--origin", "0,0,0", "--dir", "1,0,0"},  // no part
        {"info", kEmblem, "--bogus"},
        {"info", kEmblem, kEmblem},
        {"render", kEmblem},                                  // no -o
        {"render", kEmblem, "-o", (dir / "x.jpg").string()},  // unsupported format
        {"render", kEmblem, "-o", (dir / "x.png").string(), "--size", "0x10"},
        {"render", kEmblem, "-o", (dir / "x.png").string(), "--size", "big"},
        {"render", kEmblem, "-o", (dir / "x.png").string(), "--format", "jpg"},
        {"info", kEmblem, "-D", "novalue"},
        {"info", kEmblem, "--diagnostics=xml"},
        {"info", kEmblem, "--polygon-method", "woop"},
        {"bench"},                                             // no report
        {"bench", "accuracy"},                                 // no -o
        {"bench", "accuracy", "-o", "r", "--min-time", "61"},  // above 60 s
        {"bench", "accuracy", "-o", "r", "--min-time", "1s"},
        {"bench", "accuracy", "-o", "r", "-D", "x=1"},
        {"bench", "speed", "-o", "r"},
    };
    for (const auto& args : bad) {
        const RunResult r = runCsgray(args, dir.path());
        std::string joined;
        for (const auto& a : args) joined += a + " ";
        EXPECT_EQ(r.exitCode, 2) << joined << "\n" << r.err;
        EXPECT_EQ(r.out, "") << joined;
        EXPECT_FALSE(r.err.empty()) << joined;
    }
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// ---- bad models: exit 1, file:line:col on stderr ----

TEST(BadModel, SyntaxErrorIsReportedAtItsLine) {
    ScratchDir dir;
    writeFile(dir / "bad.scad", "cube(1);\nsphere(;\n");
    const RunResult r = runCsgray({"info", (dir / "bad.scad").string()}, dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("bad.scad:2:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(": error: "), std::string::npos) << r.err;
}

TEST(BadModel, CompileErrorNamesTheOffendingStatement) {
    ScratchDir dir;
    // Each scale is fine alone (the evaluator drops only a transform that is itself singular,
    // as OpenSCAD does); their product underflows to a singular matrix, which compile finds
    // and names by the statement on line 2.
    writeFile(dir / "flat.scad", "cube(1);\nscale(1e-200) scale(1e-200) cube(1);\n");
    const RunResult r = runCsgray(
        {"probe", (dir / "flat.scad").string(), "--origin", "0,0,0", "--dir", "1,0,0"}, dir.path());
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("flat.scad:2:"), std::string::npos) << r.err;
}

TEST(BadModel, BadRayLineExitsWithOneAndNamesTheLine) {
    ScratchDir dir;
    writeFile(dir / "rays.txt", "-5 0.8 0.8 1 0 0\n# a comment\n\n-5 0 0 1 0\n");
    const RunResult r =
        runCsgray({"probe", kEmblem, "--rays", (dir / "rays.txt").string()}, dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("rays.txt:4:"), std::string::npos) << r.err;
    // The good ray before the bad line was answered.
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
}

// ---- I/O errors: exit 3 ----

TEST(IoError, MissingPartUnwritableOutputMissingRaysFile) {
    ScratchDir dir;
    const RunResult missing = runCsgray({"info", (dir / "nope.scad").string()}, dir.path());
    EXPECT_EQ(missing.exitCode, 3) << missing.err;
    EXPECT_NE(missing.err.find("nope.scad"), std::string::npos);

    const RunResult noDir = runCsgray(
        {"render", kEmblem, "-o", (dir / "no/such/dir/out.png").string(), "--size", "16x16"},
        dir.path());
    EXPECT_EQ(noDir.exitCode, 3) << noDir.err;

    const RunResult noRays =
        runCsgray({"probe", kEmblem, "--rays", (dir / "nope.txt").string()}, dir.path());
    EXPECT_EQ(noRays.exitCode, 3) << noRays.err;
}

// ---- no partial output ----

std::vector<std::string> listDir(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

TEST(NoPartialOutput, FailedRenderOfABadModelLeavesNoFile) {
    ScratchDir dir;
    writeFile(dir / "bad.scad", "difference() { cube(1); sphere(; }\n");
    const RunResult r = runCsgray(
        {"render", (dir / "bad.scad").string(), "-o", (dir / "out.png").string()}, dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"bad.scad"});
}

TEST(NoPartialOutput, FailedRenderKeepsAnExistingFileUntouched) {
    ScratchDir dir;
    writeFile(dir / "out.png", "the previous image");
    writeFile(dir / "bad.scad", "cube(undefined_module_call());\n");
    const RunResult r = runCsgray(
        {"render", (dir / "bad.scad").string(), "-o", (dir / "out.png").string()}, dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(readFile(dir / "out.png"), "the previous image");
    EXPECT_EQ(listDir(dir.path()), (std::vector<std::string>{"bad.scad", "out.png"}));
}

TEST(NoPartialOutput, FailedWriteRemovesTheTemporaryFile) {
    ScratchDir dir;
    // The target is a directory: the image is written to a temporary file, and the final
    // rename fails, which must remove the temporary file (exit 3).
    fs::create_directory(dir / "taken.png");
    const RunResult r = runCsgray(
        {"render", kEmblem, "-o", (dir / "taken.png").string(), "--size", "32x24"}, dir.path());
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"taken.png"});
    EXPECT_TRUE(fs::is_empty(dir / "taken.png"));
}

// ---- diagnostics as JSON ----

TEST(JsonDiagnostics, StderrIsOneValidJsonArray) {
    ScratchDir dir;
    writeFile(dir / "bad \"quoted\".scad", "echo(\"tab\there\");\ncube([1, 2);\n");
    const RunResult r = runCsgray(
        {"info", (dir / "bad \"quoted\".scad").string(), "--diagnostics=json"}, dir.path());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.out, "");
    const auto json = nlohmann::json::parse(r.err);  // throws (fails the test) if invalid
    ASSERT_TRUE(json.is_array());
    bool sawError = false;
    for (const auto& d : json) {
        ASSERT_TRUE(d.contains("file") && d.contains("line") && d.contains("col") &&
                    d.contains("severity") && d.contains("message"))
            << d;
        if (d["severity"] == "error") {
            sawError = true;
            EXPECT_EQ(d["line"], 2);
            EXPECT_NE(d["file"].get<std::string>().find("bad \"quoted\".scad"), std::string::npos);
        }
    }
    EXPECT_TRUE(sawError) << r.err;
}

TEST(JsonDiagnostics, SuccessWithEchoKeepsStdoutCleanAndStderrValid) {
    ScratchDir dir;
    writeFile(dir / "echo.scad", "echo(\"hello\");\ncube(1);\n");
    const RunResult r = runCsgray({"probe", (dir / "echo.scad").string(), "--origin", "-1,0.5,0.5",
                                   "--dir", "1,0,0", "--diagnostics=json"},
                                  dir.path());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const auto out = nlohmann::json::parse(r.out);
    EXPECT_EQ(out["spans"].size(), 1u);
    const auto err = nlohmann::json::parse(r.err);
    ASSERT_EQ(err.size(), 1u);
    EXPECT_EQ(err[0]["severity"], "note");
    EXPECT_NE(err[0]["message"].get<std::string>().find("hello"), std::string::npos);
}

// ---- probe output ----

TEST(Probe, OutputIsOneJsonObjectWithNormalsAndObjects) {
    ScratchDir dir;
    // Along x at y = z = 0.8 through the emblem: in and out through the sphere r = 1.35.
    const RunResult r =
        runCsgray({"probe", kEmblem, "--origin", "-5,0.8,0.8", "--dir", "2,0,0"}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["ray"]["dir"], nlohmann::json::parse("[1,0,0]"));  // normalized
    ASSERT_EQ(json["spans"].size(), 1u);
    const auto& in = json["spans"][0]["in"];
    const double x = -std::sqrt(1.35 * 1.35 - 2 * 0.64);
    EXPECT_NEAR(in["t"].get<double>(), 5 + x, 1e-12);
    EXPECT_NEAR(in["point"][0].get<double>(), x, 1e-12);
    // The outward normal of the sphere at that point is the point over the radius.
    EXPECT_NEAR(in["normal"][0].get<double>(), x / 1.35, 1e-12);
    EXPECT_NEAR(in["normal"][1].get<double>(), 0.8 / 1.35, 1e-12);
    EXPECT_EQ(in["object"]["primitive"], "sphere");
    EXPECT_NE(in["object"]["source"].get<std::string>().find("emblem.scad:"), std::string::npos);
    EXPECT_NE(in["object"]["module"].get<std::string>().find("sphere"), std::string::npos);
    EXPECT_FALSE(in.contains("inside"));
}

// --polygon-method reaches the compiled mesh: a low regular 8-sided pyramid (apex 0.2 above a
// unit circle, faces 24.4 degrees apart at most, under the 30-degree crease) probed just beside
// its apex. The watertight test answers the face's own normal, whose z component is
// cos(22.5 deg) / hypot(cos(22.5 deg), 0.2) = 0.97736; Snyder's and Marchal's interpolate the
// corner normals, the apex's being +z: within 0.0022 of the apex (3e-3 of the way to the
// rim), z above 0.9999.
TEST(Probe, PolygonMethodChangesTheMeshNormal) {
    ScratchDir dir;
    writeFile(
        dir / "pyramid.scad",
        "polyhedron(concat([[0, 0, 0.2]], [for (k = [0:7]) [cos(45 * k), sin(45 * k), 0]]), "
        "concat([for (k = [0:7]) [0, 1 + (k + 1) % 8, 1 + k]], [[1, 2, 3, 4, 5, 6, 7, 8]]));");
    const double flatZ = std::cos(M_PI / 8) / std::hypot(std::cos(M_PI / 8), 0.2);
    for (const char* method : {"watertight", "snyder", "marchal"}) {
        const RunResult r =
            runCsgray({"probe", (dir / "pyramid.scad").string(), "--origin", "0.001,0.002,1",
                       "--dir", "0,0,-1", "--polygon-method", method},
                      dir.path());
        ASSERT_EQ(r.exitCode, 0) << method << ": " << r.err;
        const auto json = nlohmann::json::parse(r.out);
        ASSERT_EQ(json["spans"].size(), 1u) << r.out;
        const auto& in = json["spans"][0]["in"];
        EXPECT_EQ(in["object"]["primitive"], "polyhedron");
        const double z = in["normal"][2].get<double>();
        if (std::string(method) == "watertight")
            EXPECT_NEAR(z, flatZ, 1e-12) << r.out;
        else
            EXPECT_GT(z, 0.9999) << method << ": " << r.out;
        // The span itself is the mesh's in every method: in just below the apex, out at z = 0.
        EXPECT_NEAR(json["spans"][0]["out"]["t"].get<double>(), 1.0, 1e-12) << method;
    }
}

TEST(Probe, RayStartingInsideBeginsAtZeroMarkedInside) {
    ScratchDir dir;
    const RunResult r =
        runCsgray({"probe", kEmblem, "--origin", "0,0.8,0.8", "--dir", "1,0,0"}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    ASSERT_EQ(json["spans"].size(), 1u);
    const auto& in = json["spans"][0]["in"];
    EXPECT_EQ(in["t"].get<double>(), 0.0);
    EXPECT_EQ(in["inside"], true);
    EXPECT_TRUE(in["normal"].is_null());
    // The cut bores make a difference's normal point into the bore: here the span ends on the
    // sphere, whose normal points away from the centre.
    EXPECT_GT(json["spans"][0]["out"]["normal"][0].get<double>(), 0.0);
}

TEST(Probe, DefineOverridesATopLevelVariable) {
    ScratchDir dir;
    // bore = 0.2: the y bore now removes only |x| <= 0.2 at y = 0.7, z = 0.
    const RunResult r = runCsgray(
        {"probe", kEmblem, "-D", "bore=0.2", "--origin", "-5,0.7,0", "--dir", "1,0,0"}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto spans = spansOf(nlohmann::json::parse(r.out));
    EXPECT_TRUE(sameSpans(spans, {{4, 4.8}, {5.2, 6}}, 1e-9)) << describe(spans);
}

// "-D name=value ... may be repeated" is in every part command's help: probe above; here info,
// render, export and compare (view: viewer_test). The part refuses to load unless both -D
// values reach it (its assert), and info's bounds and the export's vertices show the size.
TEST(Define, EveryPartCommandTakesIt) {
    ScratchDir dir;
    const fs::path part = dir / "sized.scad";
    writeFile(part,
              "s = 1;\nk = 0;\nassert(s == 3 && k == 2, \"-D did not reach the part\");\n"
              "cube(s);\n");
    const std::vector<std::string> defines = {"-D", "s=3", "-D", "k=1+1"};
    const auto with = [&](std::vector<std::string> args) {
        args.insert(args.begin() + 2, defines.begin(), defines.end());
        return args;
    };
    // Without them the assert fails: a bad model.
    EXPECT_EQ(runCsgray({"info", part.string()}, dir.path()).exitCode, 1);
    const RunResult info = runCsgray(with({"info", part.string()}), dir.path());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    for (int a = 0; a < 3; ++a)
        EXPECT_EQ(nlohmann::json::parse(info.out)["bounds"]["max"][a].get<double>(), 3.0);
    const RunResult render = runCsgray(
        with({"render", part.string(), "-o", (dir / "r.png").string(), "--size", "16x12"}),
        dir.path());
    EXPECT_EQ(render.exitCode, 0) << render.err;
    const RunResult exported =
        runCsgray(with({"export", part.string(), "-o", (dir / "e.obj").string()}), dir.path());
    ASSERT_EQ(exported.exitCode, 0) << exported.err;
    double top = 0.0;
    std::istringstream obj(readFile(dir / "e.obj"));
    for (std::string line; std::getline(obj, line);)
        if (line.rfind("v ", 0) == 0) top = std::max(top, std::stod(line.substr(line.rfind(' '))));
    EXPECT_EQ(top, 3.0);
    const RunResult compare =
        runCsgray(with({"compare", part.string(), (dir / "e.obj").string(), "--json"}), dir.path());
    EXPECT_EQ(compare.exitCode, 0) << compare.err;
    EXPECT_NEAR(nlohmann::json::parse(compare.out)["volume"]["mesh"].get<double>(), 27.0, 1e-4);
}

// info's "plan" is render's plan with render's defaults: a scene whose mirror cube can shadow
// the sphere gets shadow rays for its one light (and says why), reflection on, refraction
// off, each material's own effects, and render's default min weight and depth.
TEST(Info, PlanIsTheRenderersWithItsDefaults) {
    ScratchDir dir;
    const fs::path part = dir / "plan.scad";
    writeFile(part,
              "light([0, 0, 10]);\nsphere(1);\n"
              "material(reflect = 0.5) translate([0, 5, 0]) cube(1);\n");
    const RunResult r = runCsgray({"info", part.string()}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json plan = nlohmann::json::parse(r.out)["plan"];
    EXPECT_EQ(plan["reflection"], true) << plan;
    EXPECT_EQ(plan["refraction"], false) << plan;
    EXPECT_EQ(plan["minWeight"], 1.0 / 256) << plan;
    EXPECT_EQ(plan["maxDepth"], 10) << plan;
    ASSERT_EQ(plan["lights"].size(), 1u) << plan;
    EXPECT_EQ(plan["lights"][0]["shadowRays"], true) << plan;
    EXPECT_EQ(plan["lights"][0]["position"], nlohmann::json::parse("[0, 0, 10]")) << plan;
    EXPECT_FALSE(plan["lights"][0]["why"].get<std::string>().empty()) << plan;
    ASSERT_EQ(plan["materials"].size(), 2u) << plan;
    EXPECT_EQ(plan["materials"][0]["reflection"], false) << plan;
    EXPECT_EQ(plan["materials"][1]["reflection"], true) << plan;
    // One convex solid cannot shadow itself: no shadow rays, as render decides.
    writeFile(part, "light([0, 0, 10]);\nsphere(1);\n");
    const nlohmann::json alone =
        nlohmann::json::parse(runCsgray({"info", part.string()}, dir.path()).out)["plan"];
    EXPECT_EQ(alone["convexScene"], true) << alone;
    EXPECT_EQ(alone["lights"][0]["shadowRays"], false) << alone;
}

TEST(Probe, RaysFromStdinGiveOneLinePerRayInOrder) {
    ScratchDir dir;
    std::string rays;
    for (int i = 0; i < 1000; ++i) rays += "-5 0.8 0.8 1 0 0\n0 0 5 0 0 -1\n";
    writeFile(dir / "rays.txt", rays);
    const RunResult r = runCsgray({"probe", kEmblem, "--rays", "-", "--threads", "2"}, dir.path(),
                                  (dir / "rays.txt").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string line;
    int n = 0;
    while (std::getline(lines, line)) {
        const auto json = nlohmann::json::parse(line);
        EXPECT_EQ(json["spans"].size(), n % 2 == 0 ? 1u : 0u) << "line " << n;
        ++n;
    }
    EXPECT_EQ(n, 2000);
}

// ---- info ----

TEST(Info, CountsBoundsAndTreeOfTheEmblem) {
    ScratchDir dir;
    const RunResult r = runCsgray({"info", kEmblem}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const auto json = nlohmann::json::parse(r.out);
    const auto& counts = json["counts"];
    EXPECT_EQ(counts["leaves"]["cube"], 1);
    EXPECT_EQ(counts["leaves"]["sphere"], 1);
    EXPECT_EQ(counts["leaves"]["cylinder"], 3);
    EXPECT_EQ(counts["intersections"], 1);
    EXPECT_EQ(counts["differences"], 1);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(json["bounds"]["min"][a].get<double>(), -1.0, 1e-12);
        EXPECT_NEAR(json["bounds"]["max"][a].get<double>(), 1.0, 1e-12);
    }
    EXPECT_EQ(json["tree"]["op"], "difference");
    EXPECT_NE(json["tree"]["source"].get<std::string>().find("emblem.scad:"), std::string::npos);
}

// Every leaf is named as the language names it, in info's tree and counts and in probe's
// objects: a surface() leaf is "surface", not a generic "primitive" (each primitive owns its
// name; a table written beside the primitive set had missed the newer kinds).
TEST(Info, EveryLeafKindIsNamedAndDescribed) {
    ScratchDir dir;
    const fs::path part = dir.path() / "kinds.scad";
    writeFile(part,
              "cube(1); sphere(1); cylinder(h = 1, r = 1); halfspace([1, 0, 0], -20);\n"
              "torus(R = 2, r = 0.5);\n"
              "surface(f = \"x^2 + y^2 + z^2 - 9\", bbox = [[-4, -4, -4], [4, 4, 4]]);\n");
    const RunResult r = runCsgray({"info", part.string()}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    const auto& leaves = json["counts"]["leaves"];
    for (const char* kind : {"cube", "sphere", "cylinder", "halfspace", "torus", "surface"})
        EXPECT_EQ(leaves[kind], 1) << kind;
    EXPECT_EQ(leaves["bezier_patches"], 0);  // every kind is listed, used or not
    EXPECT_FALSE(leaves.contains("primitive"));
    std::map<std::string, nlohmann::json> byOp;  // the leaves of the binary union tree
    std::vector<nlohmann::json> stack{json["tree"]};
    while (!stack.empty()) {
        const nlohmann::json node = stack.back();
        stack.pop_back();
        if (node.contains("children"))
            for (const auto& child : node["children"]) stack.push_back(child);
        else
            byOp[node["op"]] = node;
    }
    ASSERT_EQ(byOp.size(), 6u) << json["tree"];
    EXPECT_EQ(byOp["sphere"]["r"], 1);
    EXPECT_EQ(byOp["cylinder"]["h"], 1);
    EXPECT_EQ(byOp["halfspace"]["offset"], -20);
    EXPECT_EQ(byOp["torus"]["R"], 2);
    EXPECT_EQ(byOp["surface"]["degree"], 2);
    EXPECT_EQ(byOp["surface"]["bbox"], nlohmann::json::parse("[[-4,-4,-4],[4,4,4]]"));

    // Up the z axis from z = -10, the ball of radius 3 of surface() holds every other leaf
    // the ray meets: one span, from t = 7 to 13, both ends on the surface.
    const RunResult p =
        runCsgray({"probe", part.string(), "--origin", "0,0,-10", "--dir", "0,0,1"}, dir.path());
    ASSERT_EQ(p.exitCode, 0) << p.err;
    const auto spans = nlohmann::json::parse(p.out)["spans"];
    ASSERT_EQ(spans.size(), 1u) << p.out;
    EXPECT_NEAR(spans[0]["in"]["t"].get<double>(), 7.0, 1e-12);
    EXPECT_NEAR(spans[0]["out"]["t"].get<double>(), 13.0, 1e-12);
    EXPECT_EQ(spans[0]["in"]["object"]["primitive"], "surface") << p.out;
    EXPECT_EQ(spans[0]["out"]["object"]["primitive"], "surface") << p.out;
}

// A chain of n nested module calls takes memory linear in n: each node's module path is one
// step below its parent's, not a string of the whole chain (at n = 8000 that string form took
// 4.5 GB; this run takes tens of MB). Peak memory is read from the children's rusage, which
// in a test process of its own (gtest_discover_tests) is this csgray run's.
TEST(Resources, DeepModuleRecursionTakesLinearMemory) {
    ScratchDir dir;
    const fs::path part = dir.path() / "deep.scad";
    writeFile(part, "module r(n) { if (n > 0) union() { cube(1); r(n - 1); } }\nr(8000);\n");
    const RunResult r =
        runCsgray({"probe", part.string(), "--origin", "0.5,0.5,-5", "--dir", "0,0,1"}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto spans = nlohmann::json::parse(r.out)["spans"];
    ASSERT_EQ(spans.size(), 1u);  // 8000 coincident unit cubes are one cube
    EXPECT_EQ(spans[0]["out"]["object"]["module"], "r() > union > cube");
    rusage usage{};
    ASSERT_EQ(getrusage(RUSAGE_CHILDREN, &usage), 0);
    EXPECT_LT(usage.ru_maxrss, 400 * 1024) << "peak resident KiB of the csgray run";
}

// Debian's MCAD (package openscad-mcad, brought by scripts/install-deps.sh) is found in the
// installation's library folder, as OpenSCAD finds it: units.scad defines inch = 25.4 mm.
TEST(Info, IncludeFindsMcadInTheLibraryFolder) {
    ScratchDir dir;
    const fs::path part = dir.path() / "units.scad";
    writeFile(part, "include <MCAD/units.scad>\ncube(inch);\n");
    const RunResult r = runCsgray({"info", part.string()}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_NEAR(json["bounds"]["max"][0].get<double>(), 25.4, 1e-12);
}

// ---- render ----

TEST(Render, PngDecodesWithTheRequestedSizeAndShowsThePart) {
    ScratchDir dir;
    const fs::path png = dir / "emblem.png";
    const RunResult r =
        runCsgray({"render", kEmblem, "-o", png.string(), "--size", "64x48"}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out, "");
    const csg::testing::RgbImage image = csg::testing::readPng(png);
    ASSERT_EQ(image.width, 64);
    ASSERT_EQ(image.height, 48);
    // The corner is background (the default camera frames the part with a margin); the part
    // covers much of the frame and its pixels differ from the background.
    const uint8_t* corner = image.rgb.data();
    int differing = 0;
    for (size_t i = 0; i < image.rgb.size(); i += 3)
        differing += !std::equal(corner, corner + 3, image.rgb.data() + i);
    EXPECT_GT(differing, 64 * 48 / 5);
    EXPECT_LT(differing, 64 * 48);
    EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"emblem.png"});
}

TEST(Render, EverySampleRenders) {
    ScratchDir dir;
    int rendered = 0;
    for (const auto& entry : fs::directory_iterator(CSGRAY_SAMPLES)) {
        if (entry.path().extension() != ".scad") continue;
        ++rendered;
        const fs::path png = dir / (entry.path().stem().string() + ".png");
        const RunResult r = runCsgray(
            {"render", entry.path().string(), "-o", png.string(), "--size", "40x30"}, dir.path());
        EXPECT_EQ(r.exitCode, 0) << entry.path() << "\n" << r.err;
        EXPECT_EQ(csg::testing::readPng(png).width, 40) << entry.path();
    }
    // A folder that went missing or moved would render nothing and pass: samples/ has 17.
    EXPECT_GE(rendered, 17);
}

}  // namespace
}  // namespace cli
