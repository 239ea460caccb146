// csgray under mpirun (issue 22): a render, a probe --rays, an animation and an export made by
// three oversubscribed ranks are byte for byte those of one process; a job whose rank is killed
// midway fails without an output file and --resume finishes it with the same bytes.
// CSGRAY_MPIEXEC is CMake's MPIEXEC_EXECUTABLE (Open MPI's mpirun). Every command runs under
// timeout(1), so a hung job fails the test instead of hanging ctest; -k follows the TERM with a
// KILL, because a hung mpirun may not heed TERM (see KilledAnimationResumes).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "CliRunner.h"

namespace {

namespace fs = std::filesystem;
using cli::readFile;
using cli::samplePath;
using cli::ScratchDir;
using cli::shellQuote;

constexpr int kTimeoutSeconds = 120;
// How long timeout(1) waits after its TERM before it sends KILL.
constexpr int kKillAfterSeconds = 5;

struct Outcome {
    int exitCode = -1;
    std::string out, err;
};

// Runs `prefix csgray args` through sh with stdout and stderr captured in dir, killed after
// `seconds`.
Outcome run(const std::string& prefix, const std::vector<std::string>& args, const fs::path& dir,
            int seconds = kTimeoutSeconds) {
    std::string command = "timeout -k " + std::to_string(kKillAfterSeconds) + " " +
                          std::to_string(seconds) + " " + prefix + " " + shellQuote(CSGRAY_EXE);
    for (const std::string& a : args) command += " " + shellQuote(a);
    const fs::path out = dir / ".stdout", err = dir / ".stderr";
    command += " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string()) + " </dev/null";
    const int status = std::system(command.c_str());
    Outcome r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readFile(out);
    r.err = readFile(err);
    return r;
}

// mpirun for n ranks on this machine, whatever its core count and user (CI runs as root).
// The shared-memory transport copies through the kernel (CMA) by default, which containers
// often forbid: plain copies instead. env names variables to pass to every rank.
std::string mpirun(int n, const std::string& env = "") {
    std::string m = shellQuote(CSGRAY_MPIEXEC) + " -np " + std::to_string(n) + " --oversubscribe";
    if (geteuid() == 0) m += " --allow-run-as-root";
    m += " --mca btl_vader_single_copy_mechanism none";
    if (!env.empty()) m += " -x " + env;
    return m;
}

const std::string kPart = samplePath("emblem.scad").string();

std::vector<std::string> renderArgs(const fs::path& out, const std::vector<std::string>& more) {
    std::vector<std::string> args = {"render", kPart,     "-o",     out.string(),
                                     "--size", "160x120", "--quiet"};
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

TEST(CliMpi, RenderIsByteIdenticalToOneProcess) {
    ScratchDir dir;
    for (const std::string name : {"image.png", "image.pfm"}) {
        const fs::path alone = dir / ("alone_" + name), ranks = dir / ("ranks_" + name);
        const Outcome a = run("", renderArgs(alone, {"--threads", "2"}), dir.path());
        ASSERT_EQ(a.exitCode, 0) << a.err;
        const Outcome b = run(mpirun(3), renderArgs(ranks, {"--threads", "1"}), dir.path());
        ASSERT_EQ(b.exitCode, 0) << b.err;
        EXPECT_FALSE(readFile(alone).empty());
        EXPECT_TRUE(readFile(alone) == readFile(ranks)) << name << " differs";
    }
}

// An export by three ranks writes the bytes one process writes, on each path export takes
// (csg/mesh/Tessellate.h): a torus (--grid: its rows cast and its samples measured on the
// ranks), the emblem (its curves faceted, the faceted boundary measured on the ranks) and a
// box with a box cut out (the exact polyhedral boundary: its faces cut on the ranks). The same
// file name on both sides: a GLB names its mesh after it. The summary is printed once.
TEST(CliMpi, ExportIsByteIdenticalToOneProcess) {
    ScratchDir dir;
    cli::writeFile(dir / "torus.scad", "rotate_extrude() translate([3, 0]) circle(1);\n");
    cli::writeFile(dir / "box.scad", "difference() { cube(10); translate([2, 2, 2]) cube(10); }\n");
    fs::create_directories(dir / "alone");
    fs::create_directories(dir / "ranks");
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {(dir / "torus.scad").string(), {"stl", "glb", "obj", "3mf"}},
        {kPart, {"stl", "glb"}},
        {(dir / "box.scad").string(), {"stl", "3mf"}},
    };
    for (const auto& [part, formats] : cases)
        for (const std::string& format : formats) {
            SCOPED_TRACE(part + " to " + format);
            const fs::path alone = dir / "alone" / ("mesh." + format);
            const fs::path ranks = dir / "ranks" / ("mesh." + format);
            // The torus on the grid (its faceted boundary would measure within the default
            // tolerance at once), at a tolerance that takes one pass.
            std::vector<std::string> args = {"export",       part,        "-o",
                                             alone.string(), "--threads", "2"};
            if (part.ends_with("torus.scad"))
                args.insert(args.end(), {"--grid", "--tolerance", "0.01"});
            const Outcome a = run("", args, dir.path());
            ASSERT_EQ(a.exitCode, 0) << a.err;
            args[3] = ranks.string();
            args[5] = "1";
            const Outcome b = run(mpirun(3), args, dir.path());
            ASSERT_EQ(b.exitCode, 0) << b.err;
            EXPECT_GT(readFile(alone).size(), 1000u);
            EXPECT_TRUE(readFile(alone) == readFile(ranks)) << "the ranks' mesh differs";
            size_t summaries = 0;
            for (size_t at = b.err.find("csgray: export: "); at != std::string::npos;
                 at = b.err.find("csgray: export: ", at + 1))
                ++summaries;
            EXPECT_EQ(summaries, 1u) << b.err;
        }
}

// An export whose last rank dies midway fails, leaving no mesh, only the journal; restarted with
// --resume (on other ranks) it takes the journal's results instead of casting them again, says
// how many, and writes the bytes one process writes.
TEST(CliMpi, KilledExportResumes) {
    constexpr int kKilledJobSeconds = 30;  // see KilledAnimationResumes
    ScratchDir dir;
    const fs::path part = dir / "torus.scad", reference = dir / "alone" / "mesh.stl",
                   out = dir / "ranks" / "mesh.stl";
    const fs::path journal = out.string() + ".journal";
    cli::writeFile(part, "rotate_extrude() translate([3, 0]) circle(1);\n");
    fs::create_directories(reference.parent_path());
    fs::create_directories(out.parent_path());
    const auto args = [&](const fs::path& to, std::vector<std::string> more) {
        std::vector<std::string> a = {"export",    part.string(), "-o",
                                      to.string(), "--grid",      "--tolerance",
                                      "0.005",     "--threads",   "1"};
        a.insert(a.end(), more.begin(), more.end());
        return a;
    };
    ASSERT_EQ(run("", args(reference, {}), dir.path()).exitCode, 0);

    // The last rank dies in the second loop (the grid's rows were the first), after 2 of its
    // items: mpirun ends the job, and the journal holds items of both loops.
    const Outcome killed =
        run("env CSGRAY_TEST_KILL_AFTER_TASKS=2 CSGRAY_TEST_KILL_IN_FARM=1 " +
                mpirun(3, "CSGRAY_TEST_KILL_AFTER_TASKS -x CSGRAY_TEST_KILL_IN_FARM"),
            args(out, {"--resume"}), dir.path(), kKilledJobSeconds);
    EXPECT_NE(killed.exitCode, 0) << killed.err;
    EXPECT_FALSE(fs::exists(out));
    ASSERT_TRUE(fs::exists(journal));
    for (const auto& entry : fs::directory_iterator(out.parent_path()))  // no temporary mesh
        EXPECT_EQ(entry.path(), journal);
    // Its records (dist/Journal.h: a header line, then u64 id, u64 size, the bytes, u64 hash),
    // whole ones only: a record torn by the kill is dropped), and how many loops they come from
    // (the id's bits above the item's 40).
    const std::string records = readFile(journal);
    size_t count = 0, at = records.find('\n') + 1;
    std::vector<uint64_t> loops;
    for (uint64_t id = 0, size = 0; at + 16 <= records.size(); at += 24 + size, ++count) {
        std::memcpy(&id, records.data() + at, 8);
        std::memcpy(&size, records.data() + at + 8, 8);
        if (size > records.size() - at - 16 || records.size() - at - 16 - size < 8) break;
        if (std::find(loops.begin(), loops.end(), id >> 40) == loops.end())
            loops.push_back(id >> 40);
    }
    EXPECT_EQ(loops.size(), 2u);

    const Outcome resumed = run(mpirun(2), args(out, {"--resume", "--verbose"}), dir.path());
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_TRUE(readFile(out) == readFile(reference)) << "the resumed mesh differs";
    EXPECT_FALSE(fs::exists(journal));
    const std::string said = "--resume: ";
    const size_t told = resumed.err.find(said);
    ASSERT_NE(told, std::string::npos) << resumed.err;
    EXPECT_EQ(std::strtoull(resumed.err.c_str() + told + said.size(), nullptr, 10), count)
        << "every record of the journal is taken: " << resumed.err;
}

// Rays that cross the emblem from every side, some missing it, in a fixed order.
std::string raysText(int count) {
    std::string text = "# ox oy oz dx dy dz\n";
    uint64_t state = 12345;
    auto next = [&]() {  // a small LCG: the same rays on every run
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53 * 2.0 - 1.0;
    };
    for (int i = 0; i < count; ++i) {
        char line[200];
        std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", 60 * next(),
                      60 * next(), 60 * next(), next(), next(), next() + 0.001);
        text += line;
    }
    return text;
}

TEST(CliMpi, ProbeRaysAreInInputOrder) {
    ScratchDir dir;
    const fs::path rays = dir / "rays.txt";
    cli::writeFile(rays, raysText(5000));
    const std::vector<std::string> args = {"probe", kPart, "--rays", rays.string()};
    const Outcome alone = run("", args, dir.path());
    ASSERT_EQ(alone.exitCode, 0) << alone.err;
    const Outcome ranks =
        run(mpirun(3), {"probe", kPart, "--rays", rays.string(), "--threads", "1"}, dir.path());
    ASSERT_EQ(ranks.exitCode, 0) << ranks.err;
    EXPECT_EQ(std::count(alone.out.begin(), alone.out.end(), '\n'), 5000);
    EXPECT_TRUE(alone.out == ranks.out) << "the ranks' lines differ from one process's";

    // A bad line: the rays before it are printed, then the error (exit 1), as alone.
    cli::writeFile(rays, raysText(3000) + "1 2 3\n" + raysText(10));
    const Outcome bad =
        run(mpirun(3), {"probe", kPart, "--rays", rays.string(), "--threads", "1"}, dir.path());
    EXPECT_EQ(bad.exitCode, 1) << bad.err;
    EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 3000);
    EXPECT_NE(bad.err.find(":3002:"), std::string::npos) << bad.err;
}

TEST(CliMpi, KilledRankLeavesNoImageAndResumeFinishesIt) {
    ScratchDir dir;
    const fs::path reference = dir / "reference.png", out = dir / "out.png";
    const fs::path journal = out.string() + ".journal";
    // 300 tiles of 4 samples a pixel, so that the last rank is still busy when it dies.
    const std::vector<std::string> big = {"--size", "320x240", "--threads", "1", "--aa", "2"};
    const Outcome a = run("", renderArgs(reference, big), dir.path());
    ASSERT_EQ(a.exitCode, 0) << a.err;

    // The last rank dies (SIGKILL) after 6 tiles of the 300: mpirun ends the job.
    const Outcome killed =
        run("env CSGRAY_TEST_KILL_AFTER_TASKS=6 " + mpirun(3, "CSGRAY_TEST_KILL_AFTER_TASKS"),
            renderArgs(out, {"--size", "320x240", "--threads", "1", "--aa", "2", "--resume"}),
            dir.path());
    EXPECT_NE(killed.exitCode, 0) << killed.err;
    EXPECT_FALSE(fs::exists(out));
    ASSERT_TRUE(fs::exists(journal));
    for (const auto& entry : fs::directory_iterator(dir.path()))  // no temporary image either
        EXPECT_TRUE(entry.path() == reference || entry.path() == journal ||
                    entry.path().filename().string().starts_with(".std"))
            << entry.path();

    // A record torn by the kill (here: the last 5 bytes cut off) is dropped and redone.
    const uintmax_t size = fs::file_size(journal);
    ASSERT_GT(size, 100u);
    fs::resize_file(journal, size - 5);

    // Restarted (on two ranks), it renders what is missing: the same bytes, no journal left.
    const Outcome resumed =
        run(mpirun(2),
            renderArgs(out, {"--size", "320x240", "--threads", "1", "--aa", "2", "--resume"}),
            dir.path());
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_TRUE(readFile(out) == readFile(reference));
    EXPECT_FALSE(fs::exists(journal));
}

TEST(CliMpi, ResumeAloneRendersTheSameImage) {
    ScratchDir dir;
    const fs::path reference = dir / "reference.pfm", out = dir / "out.pfm";
    ASSERT_EQ(run("", renderArgs(reference, {}), dir.path()).exitCode, 0);
    // A journal of another job (other options) is not used: it is replaced.
    cli::writeFile(out.string() + ".journal", "csgray-journal 1 0123456789abcdef\nrest");
    const Outcome r = run("", renderArgs(out, {"--resume"}), dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(readFile(out) == readFile(reference));
    EXPECT_FALSE(fs::exists(out.string() + ".journal"));
}

// $t as `openscad --animate 4` steps it (0, 0.25, 0.5, 0.75), OpenSCAD's file names, and the
// frames spread over the ranks giving the same files.
TEST(CliMpi, AnimationFramesMatchOneProcess) {
    ScratchDir dir;
    const fs::path part = dir / "spin.scad";
    cli::writeFile(part, "rotate([0, 0, $t * 90]) cube([20, 8, 4], center = true);\n");
    const auto args = [&](const fs::path& out) {
        return std::vector<std::string>{"render", part.string(), "-o", out.string(), "--size",
                                        "64x48",  "--animate",   "4",  "--quiet"};
    };
    ASSERT_EQ(run("", args(dir / "alone.png"), dir.path()).exitCode, 0);
    const Outcome r = run(mpirun(3), args(dir / "ranks.png"), dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (int f = 0; f < 4; ++f) {
        const std::string digits = "0000" + std::to_string(f);
        const std::string alone = readFile(dir / ("alone" + digits + ".png"));
        EXPECT_FALSE(alone.empty()) << "frame " << f;
        EXPECT_TRUE(alone == readFile(dir / ("ranks" + digits + ".png"))) << "frame " << f;
    }
    EXPECT_TRUE(readFile(dir / "alone00000.png") != readFile(dir / "alone00001.png"));
    // Frame 2 alone is $t = 0.5, also when asked by --frames 2:2.
    ASSERT_EQ(run("",
                  {"render", part.string(), "-o", (dir / "one.png").string(), "--size", "64x48",
                   "--frames", "2:2", "--animate", "4", "--quiet"},
                  dir.path())
                  .exitCode,
              0);
    EXPECT_TRUE(readFile(dir / "one00002.png") == readFile(dir / "alone00002.png"));
    EXPECT_FALSE(fs::exists(dir / "one00001.png"));
}

// Frames: a job whose last rank dies after its first frame fails, leaves only whole frame files
// and the journal; --resume renders the frames that are missing, the same bytes as alone.
// Debian's mpirun (Open MPI 4.1.4) sometimes deadlocks in PMIx_server_finalize after a rank has
// died and every other rank has exited (about 1 run in 15 with another job beside it), and then
// ignores TERM. The killed job therefore gets a short timeout: by then it has failed either way.
TEST(CliMpi, KilledAnimationResumes) {
    constexpr int kKilledJobSeconds = 30;  // the job takes under a second when mpirun does not hang
    ScratchDir dir;
    const fs::path part = dir / "spin.scad";
    cli::writeFile(part, "rotate([0, 0, $t * 90]) cube([20, 8, 4], center = true);\n");
    const auto args = [&](const fs::path& out) {
        return std::vector<std::string>{"render",  part.string(), "-o",        out.string(),
                                        "--size",  "96x72",       "--animate", "6",
                                        "--quiet", "--threads",   "1",         "--resume"};
    };
    ASSERT_EQ(run("", args(dir / "alone.png"), dir.path()).exitCode, 0);
    const Outcome killed =
        run("env CSGRAY_TEST_KILL_AFTER_TASKS=1 " + mpirun(3, "CSGRAY_TEST_KILL_AFTER_TASKS"),
            args(dir / "ranks.png"), dir.path(), kKilledJobSeconds);
    EXPECT_NE(killed.exitCode, 0) << killed.err;
    EXPECT_TRUE(fs::exists(dir / "ranks.png.journal"));
    const Outcome resumed = run("", args(dir / "ranks.png"), dir.path());
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    for (int f = 0; f < 6; ++f) {
        const std::string digits = "0000" + std::to_string(f);
        EXPECT_TRUE(readFile(dir / ("alone" + digits + ".png")) ==
                    readFile(dir / ("ranks" + digits + ".png")))
            << "frame " << f;
    }
    EXPECT_FALSE(fs::exists(dir / "ranks.png.journal"));
    EXPECT_FALSE(fs::exists(dir / "alone.png.journal"));
}

}  // namespace
