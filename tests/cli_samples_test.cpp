// End-to-end tests of `csgray probe` on every part in samples/: spans along chosen rays
// against spans derived by hand from each part's dimensions (not from csgray), and the
// OpenSCAD round trip (openscad -o x.csg, then the same rays through the .csg).
//
// Each ray below is axis-aligned with a unit direction, so t is the distance from the origin
// to a face; the comment above each case says which faces the ray crosses.
#include <chrono>
#include <cmath>
#include <map>
#include <random>

#include "CliRunner.h"
#include "MissingTool.h"

namespace cli {
namespace {

using Vec = std::array<double, 3>;

struct ProbeCase {
    Vec origin, dir;
    std::vector<SpanT> expected;
};

// Half the width at height h of the regular n-gon of circumradius r with a vertex on +x, as
// OpenSCAD's circle(r, $fn = n) places it (n a multiple of 4, so it is symmetric about both
// axes): on the side between the vertices at angles 360 k / n and 360 (k + 1) / n whose
// heights enclose h, linearly between the two.
double ngonHalfWidth(double r, int n, double h) {
    h = std::abs(h);
    for (int k = 0; k < n / 4; ++k) {
        const double a0 = 2 * M_PI * k / n, a1 = 2 * M_PI * (k + 1) / n;
        const double y0 = r * std::sin(a0), y1 = r * std::sin(a1);
        if (h <= y1)
            return r * std::cos(a0) + (h - y0) / (y1 - y0) * r * (std::cos(a1) - std::cos(a0));
    }
    return 0.0;
}

// Spans of the grid row j = k = 0 of csg_grid.scad along x at y = 0.4, z = 0, from x = -2.
// The part sets $fn = 64, so (--curves auto) its sphere and bores are OpenSCAD's polyhedra.
// Part i sits at x = 1.2 i, turned 13 i degrees about x, so the ray meets it at local
// y' = 0.4 cos, z' = -0.4 sin: the cube bounds |x'| <= 0.5 (the faceted sphere r = 0.68 keeps
// every facet over 0.678 from its centre, beyond (0.5, 0.4)'s 0.64), the z bore misses
// (y' > 0.3, and its 64-gon lies within r = 0.3) and the y bore removes x' inside its 64-gon
// of radius 0.3 in the x'-z' plane (rotate([90, 0, 0]) takes the cylinder's y to z), at
// height z'.
std::vector<SpanT> gridRow() {
    std::vector<SpanT> spans;
    for (int i = 0; i < 3; ++i) {
        const double theta = 13.0 * i * M_PI / 180.0;
        const double z = 0.4 * std::sin(theta);
        const double cut = ngonHalfWidth(0.3, 64, z);
        const double c = 1.2 * i + 2.0;  // the part's centre, as a distance from x = -2
        spans.push_back({c - 0.5, c - cut});
        spans.push_back({c + cut, c + 0.5});
    }
    return spans;
}

std::map<std::string, std::vector<ProbeCase>> analyticCases() {
    std::map<std::string, std::vector<ProbeCase>> cases;
    const Vec px{1, 0, 0}, py{0, 1, 0}, mx{-1, 0, 0}, my{0, -1, 0}, mz{0, 0, -1}, pz{0, 0, 1};

    // emblem: cube 2 (|x|,|y|,|z| <= 1) n sphere 1.35, minus bores of radius 0.6 on each axis.
    const double emblemX = std::sqrt(1.35 * 1.35 - 0.8 * 0.8 - 0.8 * 0.8);
    cases["emblem.scad"] = {
        // y = z = 0.8 misses all three bores; the sphere is narrower than the cube there.
        {{-5, 0.8, 0.8}, px, {{5 - emblemX, 5 + emblemX}}},
        // y = 0.7: the y bore removes |x| <= 0.6; the cube bounds |x| <= 1.
        {{-5, 0.7, 0}, px, {{4, 4.4}, {5.6, 6}}},
        // Down the z bore: nothing.
        {{0, 0, 5}, mz, {}},
        {{0.8, 0.8, 5}, mz, {{5 - emblemX, 5 + emblemX}}},
        // Starting inside: the first span begins at t = 0.
        {{0, 0.8, 0.8}, px, {{0, emblemX}}},
    };

    cases["csg_grid.scad"] = {{{-2, 0.4, 0}, px, gridRow()}};

    // gem: octahedron |x| + |y| + |z| <= 10 (a polyhedron) n box |x|, |y| <= 7, |z| <= 6, minus
    // a bore r = 2 along z.
    const double gemBore = std::sqrt(4 - 0.25);
    cases["gem.scad"] = {
        // At (4, 1) the octahedron allows |z| <= 5, inside the box's 6.
        {{4, 1, -20}, pz, {{15, 25}}},
        // y = 0.5, z = 0: the box's |x| <= 7 (the octahedron's is 9.5), the bore |x| <= 1.936.
        {{-20, 0.5, 0}, px, {{13, 20 - gemBore}, {20 + gemBore, 27}}},
        // x = 6, z = 3: the octahedron's |y| <= 1; the bore is 6 away.
        {{6, -20, 3}, py, {{19, 21}}},
        // Down the bore: nothing.
        {{0.5, 0.5, 20}, mz, {}},
    };

    // vase: the profile revolved and lifted by 3.5, on a hexagonal foot [0, 4] with a slot
    // |y| <= 1.5 at z in [0.5, 3.5]. Down the axis: the vase's bottom, z in [3.5, 4.7], and the
    // foot under the slot, z in [0, 0.5]. Across at profile height 20 (z = 23.5): the outer
    // edge (13, 14)-(10, 24) is at r = 11.2, the inner one (11.8, 14)-(8.8, 24) at r = 10.
    cases["vase.scad"] = {
        {{0, 0, 50}, mz, {{45.3, 46.5}, {49.5, 50}}},
        {{-30, 0, 23.5}, px, {{18.8, 20}, {40, 41.2}}},
    };

    // bracket: base [0,40]x[0,20]x[0,4], upright [0,4]x[0,20]x[0,30]; holes r = 3 at
    // (15,10) and (30,10) through the base, and along x at y = 10, z = 20 through the upright.
    cases["bracket.scad"] = {
        {{8, 10, 10}, mz, {{6, 10}}},
        {{15, 10, 10}, mz, {}},
        // Up the upright at x = 2: the x hole removes 17 <= z <= 23.
        {{2, 10, 40}, mz, {{10, 17}, {23, 40}}},
        {{-5, 10, 20}, px, {}},
        {{-5, 2, 20}, px, {{5, 9}}},
        // Along the base through both holes' centres.
        {{-5, 10, 2}, px, {{5, 17}, {23, 32}, {38, 45}}},
    };

    // gear_ring: ring 12 <= r <= 20, z in [0,5]; teeth [19,24] x [-2,2] at every 22.5 degrees.
    cases["gear_ring.scad"] = {
        {{-40, 0, 2.5}, px, {{16, 28}, {52, 64}}},
        {{16, 0, 10}, mz, {{5, 10}}},
        {{22, 0, 10}, mz, {{5, 10}}},
        // Between two teeth, outside the ring.
        {{22, 5, 10}, mz, {}},
    };

    // pipe_tee: run along x (|x| <= 30), branch along +y (0 <= y <= 30), outer r 10, bore 8.
    cases["pipe_tee.scad"] = {
        {{20, 0, -20}, pz, {{10, 12}, {28, 30}}},
        // x = 9 is in the branch's wall: the run's wall, its bore, then the branch wall.
        {{9, -40, 0}, py, {{30, 32}, {48, 70}}},
        {{0, -40, 0}, py, {{30, 32}}},
        {{-40, 0, 0}, px, {}},
    };

    // pawn: foot cone r 10 -> 8 over z [0,3], stem r 6 -> 3 over [3,18], collar r 5 over
    // [14,15.5], head sphere r 5 at z = 21.
    cases["pawn.scad"] = {
        {{0, 0, 50}, mz, {{24, 50}}},
        {{-20, 0, 21}, px, {{15, 25}}},
        {{-20, 0, 1.5}, px, {{11, 29}}},
        {{-20, 0, 10}, px, {{20 - (6 - 3 * 7.0 / 15), 20 + (6 - 3 * 7.0 / 15)}}},
        {{-20, 0, 14.75}, px, {{15, 25}}},
    };

    // flange: disc r 40 over z [0,8], hub r 20 over [0,25], bore r 12, six bolt holes r 4 on
    // a circle of radius 30 starting at angle 0 (so at x = 30 and x = -30).
    cases["flange.scad"] = {
        {{-50, 0, 4}, px, {{10, 16}, {24, 38}, {62, 76}, {84, 90}}},
        {{0, 30, 30}, mz, {{22, 30}}},
        {{16, 0, 30}, mz, {{5, 30}}},
        {{30, 0, 30}, mz, {}},
    };

    // hinge: plate [2,32] x [-1,1] x [0,30]; knuckles r 4 over z [0,10] and [20,30]; pin r 1.5.
    cases["hinge.scad"] = {
        {{0, 3, 40}, mz, {{10, 20}, {30, 40}}},
        {{3, 0, 40}, mz, {{10, 40}}},
        {{-10, 0, 5}, px, {{6, 8.5}, {11.5, 42}}},
        {{-10, 0, 15}, px, {{12, 42}}},
    };

    // dice: cube 20 centred n sphere 14; pips r 2 centred on the faces: a pip at a face's
    // centre on faces 1 (+z), 3 (+y) and 5 (-x); a pip at (5,5) on face 6 (-z).
    cases["dice.scad"] = {
        {{0, 0, 20}, mz, {{12, 30}}},
        {{20, 0, 0}, mx, {{10, 28}}},
        {{0, 20, 0}, my, {{12, 30}}},
        {{5, 5, 20}, mz, {{10, 28}}},
    };

    // table: top [0,100]x[0,60]x[70,74]; legs 5 x 5 x 70 at the corners; apron z in [62,70],
    // between x in [5,95], y in [5,55], hollow inside x in [10,90], y in [10,50].
    cases["table.scad"] = {
        // Leg and top share the face z = 70: one span.
        {{2.5, 2.5, 100}, mz, {{26, 100}}},         {{50, 30, 100}, mz, {{26, 30}}},
        {{7.5, -10, 66}, py, {{15, 65}}},           {{50, -10, 66}, py, {{15, 20}, {60, 65}}},
        {{2.5, -10, 66}, py, {{10, 15}, {65, 70}}},
    };

    // knob: body cone r 15 -> 13 over z [0,16], dome = sphere 13 scaled 0.4 in z at z = 16;
    // D-shaped shaft hole r 3 over z [-1,12] minus x >= 2; flutes only for z >= 2 and
    // at 15 + 30 k degrees (none crosses y = 0 at these radii).
    const double dome = 16 + 0.4 * std::sqrt(13.0 * 13.0 - 2.5 * 2.5);
    cases["knob.scad"] = {
        {{0, 0, 30}, mz, {{30 - 21.2, 30 - 12}}},
        {{2.5, 0, 30}, mz, {{30 - dome, 30}}},
        {{-30, 0, 1}, px, {{30 - (15 - 2.0 / 16), 27}, {32, 30 + (15 - 2.0 / 16)}}},
        {{-30, 0, 8}, px, {{16, 27}, {32, 44}}},
    };

    // teapot: a surface, so each crossing is a zero-length span. Down the axis: the knob's pole
    // (0, 0, 3.15) and the bottom's pole (0, 0, 0), each shared by four patches. Along y at
    // x = 0, z = 0.9: the body's widest row (control points (0, -+2, 0.9), on the edges shared
    // by its upper and lower patches and by neighbouring quadrants); handle and spout lie at
    // |x| >= 1.5.
    cases["teapot.scad"] = {
        {{0, 0, 10}, mz, {{10 - 3.15, 10 - 3.15}, {10, 10}}},
        {{0, -10, 0.9}, py, {{8, 8}, {12, 12}}},
    };
    // The article-style patches (method "groebner"), from their monomial forms
    // (tests/PatchReference.h): S(1/2, 1/2) = (19/32, 15/32, 1/4), (37/64, 5/8, 5/32) and
    // (81/128, 81/128, 31/128), each crossed once by a vertical line; beside the patch, none.
    cases["article_patch1.scad"] = {{{19.0 / 32, 15.0 / 32, 10}, mz, {{10 - 0.25, 10 - 0.25}}},
                                    {{5, 5, 10}, mz, {}}};
    cases["article_patch2.scad"] = {
        {{37.0 / 64, 5.0 / 8, 10}, mz, {{10 - 5.0 / 32, 10 - 5.0 / 32}}}, {{5, 5, 10}, mz, {}}};
    cases["article_patch3.scad"] = {
        {{81.0 / 128, 81.0 / 128, 10}, mz, {{10 - 31.0 / 128, 10 - 31.0 / 128}}},
        {{5, 5, 10}, mz, {}}};
    return cases;
}

// "emblem.scad" -> "emblem": test names may not contain dots.
std::string sampleTestName(const ::testing::TestParamInfo<std::string>& param) {
    return param.param.substr(0, param.param.find('.'));
}

class SampleSpans : public ::testing::TestWithParam<std::string> {};

// All of a sample's rays go through one `probe --rays` run, and the first one also through
// `probe --origin --dir`, so both paths are checked against the same hand-derived spans.
TEST_P(SampleSpans, MatchHandDerivedSpans) {
    const std::string sample = GetParam();
    const auto all = analyticCases();
    ASSERT_TRUE(all.count(sample)) << "no hand-derived rays for " << sample;
    const std::vector<ProbeCase>& cases = all.at(sample);
    ScratchDir dir;

    std::string rays;
    for (const ProbeCase& c : cases) rays += vec3Arg(c.origin) + " " + vec3Arg(c.dir) + "\n";
    for (char& ch : rays)
        if (ch == ',') ch = ' ';
    writeFile(dir / "rays.txt", rays);
    const RunResult batch = runCsgray(
        {"probe", samplePath(sample).string(), "--rays", (dir / "rays.txt").string()}, dir.path());
    ASSERT_EQ(batch.exitCode, 0) << batch.err;
    EXPECT_EQ(batch.err, "");

    std::istringstream lines(batch.out);
    std::string line;
    for (const ProbeCase& c : cases) {
        ASSERT_TRUE(std::getline(lines, line)) << "fewer output lines than rays";
        const auto json = nlohmann::json::parse(line);
        const auto got = spansOf(json);
        EXPECT_TRUE(sameSpans(got, c.expected, 1e-9))
            << sample << " ray from " << vec3Arg(c.origin) << " along " << vec3Arg(c.dir)
            << "\n  expected " << describe(c.expected) << "\n  got      " << describe(got);
    }
    EXPECT_FALSE(std::getline(lines, line)) << "more output lines than rays";

    const ProbeCase& first = cases.front();
    const RunResult single = runCsgray({"probe", samplePath(sample).string(), "--origin",
                                        vec3Arg(first.origin), "--dir", vec3Arg(first.dir)},
                                       dir.path());
    ASSERT_EQ(single.exitCode, 0) << single.err;
    EXPECT_TRUE(sameSpans(spansOf(nlohmann::json::parse(single.out)), first.expected, 1e-9));
}

const std::vector<std::string> kOpenScadSamples = {
    "emblem.scad", "csg_grid.scad", "bracket.scad", "gear_ring.scad", "pipe_tee.scad",
    "pawn.scad",   "flange.scad",   "hinge.scad",   "dice.scad",      "table.scad",
    "knob.scad",   "gem.scad",      "vase.scad"};

INSTANTIATE_TEST_SUITE_P(Samples, SampleSpans, ::testing::ValuesIn(kOpenScadSamples),
                         sampleTestName);

// Samples in csgray's own language extensions (no OpenSCAD round trip for them).
const std::vector<std::string> kCsgraySamples = {"teapot.scad", "article_patch1.scad",
                                                 "article_patch2.scad", "article_patch3.scad"};
INSTANTIATE_TEST_SUITE_P(CsgraySamples, SampleSpans, ::testing::ValuesIn(kCsgraySamples),
                         sampleTestName);

TEST(SampleSpans, EverySampleHasHandDerivedRays) {
    const auto all = analyticCases();
    int checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(CSGRAY_SAMPLES)) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() != ".scad" || name.starts_with("scene_")) continue;
        ++checked;
        EXPECT_TRUE(all.count(name)) << name << " has no hand-derived probe rays";
    }
    EXPECT_GE(checked, 15);  // samples/ has 15 parts besides the scene_ files: none went missing
}

// ---- OpenSCAD round trip ----

using csg::testing::haveOpenScad;

// Rays from a sphere around the part's bounds toward random points inside them (seeded).
std::string roundTripRays(const nlohmann::json& bounds, int count) {
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Vec lo, hi;
    for (int a = 0; a < 3; ++a) {
        lo[a] = bounds.at("min")[a].get<double>();
        hi[a] = bounds.at("max")[a].get<double>();
    }
    double radius = 0;
    for (int a = 0; a < 3; ++a) radius += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    radius = std::sqrt(radius);
    std::ostringstream rays;
    rays.precision(17);
    for (int i = 0; i < count; ++i) {
        Vec target, from;
        double len = 0;
        for (int a = 0; a < 3; ++a) {
            target[a] = lo[a] + unit(random) * (hi[a] - lo[a]);
            from[a] = unit(random) - 0.5;
            len += from[a] * from[a];
        }
        for (int a = 0; a < 3; ++a) from[a] = target[a] + 2 * radius * from[a] / std::sqrt(len);
        rays << from[0] << " " << from[1] << " " << from[2] << " " << target[0] - from[0] << " "
             << target[1] - from[1] << " " << target[2] - from[2] << "\n";
    }
    return rays.str();
}

// OpenSCAD 2021.01 writes the .csg's multmatrix entries with 6 significant digits, so a part
// turned by an angle that is not a multiple of 90 degrees comes back slightly moved
// (sin 60 = 0.866025 instead of 0.8660254...): points move by up to ~1e-6 of their distance
// from the origin, and a ray that grazes a surface sees its span ends move by that over the
// sine of the grazing angle. Those parts are compared at 1e-4 of their size; every other part
// (only right angles and short decimals, which the .csg keeps exactly) must match to 1e-9.
const std::map<std::string, bool> kTurnedByNonRightAngles = {
    {"csg_grid.scad", true},
    {"gear_ring.scad", true},
    {"flange.scad", true},
    {"knob.scad", true},
    {"vase.scad", true}};  // the foot's hexagon is turned by 30 degrees

class OpenScadRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(OpenScadRoundTrip, CsgExportGivesTheSameSpans) {
    if (!haveOpenScad()) SKIP_OR_FAIL_IN_CI("openscad is not installed");
    const std::string sample = GetParam();
    ScratchDir dir;
    const fs::path csg = dir / "part.csg";
    const std::string command = "openscad -o " + shellQuote(csg.string()) + " " +
                                shellQuote(samplePath(sample).string()) + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "openscad failed on " << sample;

    const RunResult info = runCsgray({"info", samplePath(sample).string()}, dir.path());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const auto bounds = nlohmann::json::parse(info.out).at("bounds");
    double size = 0;
    for (int a = 0; a < 3; ++a)
        size = std::max(size, bounds["max"][a].get<double>() - bounds["min"][a].get<double>());

    writeFile(dir / "rays.txt", roundTripRays(bounds, 200));
    const std::string rays = (dir / "rays.txt").string();
    const RunResult scad =
        runCsgray({"probe", samplePath(sample).string(), "--rays", rays}, dir.path());
    const RunResult fromCsg = runCsgray({"probe", csg.string(), "--rays", rays}, dir.path());
    ASSERT_EQ(scad.exitCode, 0) << scad.err;
    ASSERT_EQ(fromCsg.exitCode, 0) << fromCsg.err;

    const double tol = kTurnedByNonRightAngles.count(sample) ? 1e-4 * size : 1e-9;
    std::istringstream a(scad.out), b(fromCsg.out);
    std::string lineA, lineB;
    int rayCount = 0, nonEmpty = 0;
    double worst = 0;
    while (std::getline(a, lineA)) {
        ASSERT_TRUE(std::getline(b, lineB));
        const auto sa = spansOf(nlohmann::json::parse(lineA));
        const auto sb = spansOf(nlohmann::json::parse(lineB));
        ASSERT_EQ(sa.size(), sb.size()) << sample << " ray " << rayCount << "\n  .scad "
                                        << describe(sa) << "\n  .csg  " << describe(sb);
        for (size_t i = 0; i < sa.size(); ++i)
            worst =
                std::max({worst, std::abs(sa[i].in - sb[i].in), std::abs(sa[i].out - sb[i].out)});
        nonEmpty += !sa.empty();
        ++rayCount;
    }
    EXPECT_EQ(rayCount, 200);
    EXPECT_GT(nonEmpty, 50) << "too few rays hit the part to compare anything";
    EXPECT_LE(worst, tol) << sample << ": largest span-end difference " << worst;
    RecordProperty("worst_difference", std::to_string(worst));
}

INSTANTIATE_TEST_SUITE_P(Samples, OpenScadRoundTrip, ::testing::ValuesIn(kOpenScadSamples),
                         sampleTestName);

// ---- throughput of --rays ----

TEST(ProbeRays, HundredThousandRaysThroughTheGrid) {
    ScratchDir dir;
    const RunResult info = runCsgray({"info", samplePath("csg_grid.scad").string()}, dir.path());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    constexpr int kRays = 100000;
    writeFile(dir / "rays.txt", roundTripRays(nlohmann::json::parse(info.out).at("bounds"), kRays));

    const auto start = std::chrono::steady_clock::now();
    const std::string command = shellQuote(CSGRAY_EXE) + " probe " +
                                shellQuote(samplePath("csg_grid.scad").string()) + " --rays - <" +
                                shellQuote((dir / "rays.txt").string()) + " | wc -l >" +
                                shellQuote((dir / "count.txt").string());
    ASSERT_EQ(std::system(command.c_str()), 0);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(std::stoi(readFile(dir / "count.txt")), kRays);
    const double raysPerSecond = kRays / seconds;
    std::cout << "probe --rays: " << kRays << " rays through csg_grid.scad in " << seconds
              << " s = " << raysPerSecond << " rays/s (JSON lines, piped to wc)\n";
    RecordProperty("rays_per_second", std::to_string(raysPerSecond));
    // A guard against an order-of-magnitude loss, not a speed figure (that is the recorded
    // property and bench/): 10^5 rays took 5.0 s on the shared 2-core machine at load 5 (a
    // build beside it), ~0.5 s unloaded; 60 s is 12 times the loaded run, which a 2-core CI
    // machine running two tests at once cannot reach without a real regression.
    EXPECT_LT(seconds, 60.0);
}

}  // namespace
}  // namespace cli
