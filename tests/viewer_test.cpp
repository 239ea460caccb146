// End-to-end tests of `csgray view` (issue 8): the window runs under Xvfb, started by the test
// on a free display; xdotool sends it real X input (keys, clicks, drags, the wheel). The
// window's test hook CSGRAY_VIEW_DUMP writes every finished full-resolution frame to a PNG and
// says so on stderr, which is how a test knows a frame is done and what it showed, and writes
// the text of the panel drawn over the picture to frame.png.panel.txt whenever the window
// shows a changed panel. Frames are numbered by request: every camera move, key or reload
// starts the next one. Tests skip, saying why, where Xvfb or xdotool is missing or no X server
// starts.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>
#include <utility>

#include "CliRunner.h"
#include "MissingTool.h"
#include "PngImage.h"
#include "viewer/window/SdlLibrary.h"

namespace {

using namespace cli;
using namespace std::chrono_literals;

bool onPath(const std::string& program) {
    return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

bool waitUntil(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
        if (done()) return true;
        std::this_thread::sleep_for(20ms);
    }
    return done();
}

// Starts /bin/sh -c command in dir; the pid is the shell, which execs the program.
pid_t spawn(const std::string& command, const fs::path& dir) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (::chdir(dir.c_str()) != 0) ::_exit(127);
        ::setpgid(0, 0);
        ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    return pid;
}

// Xvfb on a display number it picks itself (-displayfd): tests run in parallel, and two of
// them probing for a free number could both pick the same one and see each other's windows.
// xdotool's %1 is then the older of two same-titled windows: one test's input would reach
// the other test's view.
class VirtualDisplay {
public:
    VirtualDisplay() {
        if (!onPath("Xvfb")) {
            reason_ = "Xvfb is not installed (Debian package xvfb)";
            return;
        }
        // Xvfb writes the display number and a newline to the fd once it accepts clients.
        const fs::path numberFile =
            fs::temp_directory_path() / ("csgray-xvfb-" + std::to_string(::getpid()));
        const pid_t pid = spawn("exec Xvfb -displayfd 3 -screen 0 640x480x24 -nolisten tcp 3>'" +
                                    numberFile.string() + "' >/dev/null 2>&1",
                                fs::temp_directory_path());
        std::string number;
        if (waitUntil(
                [&] {
                    number = readFile(numberFile);
                    return number.find('\n') != std::string::npos;
                },
                10s)) {
            pid_ = pid;
            name_ = ":" + number.substr(0, number.find('\n'));
        } else {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
        fs::remove(numberFile);
        if (pid_ <= 0) reason_ = "no Xvfb server could be started";
    }
    ~VirtualDisplay() {
        if (pid_ <= 0) return;
        ::kill(pid_, SIGTERM);
        ::waitpid(pid_, nullptr, 0);
    }
    bool ok() const { return pid_ > 0; }
    const std::string& name() const { return name_; }
    const std::string& reason() const { return reason_; }

private:
    pid_t pid_ = -1;
    std::string name_, reason_;
};

using Image = csg::testing::RgbImage;
using csg::testing::readPng;

int maxDifference(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return 256;
    int worst = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        worst = std::max(worst, std::abs(a.rgb[i] - b.rgb[i]));
    return worst;
}

// The fraction of pixels that differ from the top-left (background) pixel.
double coverage(const Image& image) {
    size_t covered = 0;
    for (size_t i = 0; i < image.rgb.size(); i += 3)
        for (int c = 0; c < 3; ++c)
            if (std::abs(image.rgb[i + c] - image.rgb[c]) > 8) {
                ++covered;
                break;
            }
    return double(covered) / double(image.rgb.size() / 3);
}

const char* const kPart =
    "// two solids, one behind the other\n"
    "difference() {\n"
    "    cube(10, center = true);\n"
    "    sphere(r = 6.5);\n"
    "}\n"
    "translate([0, 12, 0]) sphere(r = 4);\n";

// Three effects the S, M and T keys switch off: a floor that catches the spheres' shadows, a
// mirror sphere and a glass one.
const char* const kEffectsPart =
    "camera(eye = [0, -20, 9], center = [0, 0, 0], up = [0, 0, 1], fov = 40);\n"
    "light(position = [6, -8, 14]);\n"
    "material(color = [0.8, 0.8, 0.8]) translate([0, 0, -3]) cube([30, 30, 1], center = true);\n"
    "material(color = [0.9, 0.2, 0.2], reflect = 0.6) translate([-3.5, 0, 0]) sphere(2.5);\n"
    "material(color = [0.2, 0.4, 0.9], transmit = 0.7, ior = 1.5) translate([3.5, 0, 0])\n"
    "    sphere(2.5);\n";

constexpr int kWidth = 160, kHeight = 120;

// One `csgray view` under the display, its stderr in a file, frames dumped to frame.png.
class ViewerTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { display_ = new VirtualDisplay(); }
    static void TearDownTestSuite() {
        delete display_;
        display_ = nullptr;
    }

    void SetUp() override {
        if (!display_->ok()) SKIP_OR_FAIL_IN_CI(display_->reason());
        part_ = dir_ / "part.scad";
        writeFile(part_, kPart);
    }
    void TearDown() override {
        if (pid_ > 0) {
            ::kill(-pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }

    // SDL_MOUSE_FOCUS_CLICKTHROUGH: a test's first xdotool windowfocus moves the focus from
    // PointerRoot to the window, and SDL drops a click it reads within 10 ms of that FocusIn
    // (a click that activates a window is not passed on unless this hint says so). Under load
    // the click often arrives in the same batch, and the first click or drag was lost.
    void launch(const std::string& extraArgs = "") {
        const std::string command = "DISPLAY=" + display_->name() +
                                    " SDL_MOUSE_FOCUS_CLICKTHROUGH=1"
                                    " CSGRAY_VIEW_DUMP=frame.png exec " +
                                    shellQuote(CSGRAY_EXE) + " view part.scad --size " +
                                    std::to_string(kWidth) + "x" + std::to_string(kHeight) +
                                    " --threads 2 --verbose " + extraArgs + " 2>stderr.txt";
        pid_ = spawn(command, dir_.path());
    }
    std::string err() const { return readFile(dir_ / "stderr.txt"); }
    // The panel as the window last showed it (empty before the first present).
    std::string panel() const {
        const fs::path file = dir_ / "frame.png.panel.txt";
        return fs::exists(file) ? readFile(file) : std::string();
    }
    bool waitForPanel(const std::function<bool(const std::string&)>& shows) {
        return waitUntil([&] { return shows(panel()); }, 8s);
    }
    static bool has(const std::string& text, const std::string& part) {
        return text.find(part) != std::string::npos;
    }
    Image frame() const { return readPng(dir_ / "frame.png"); }
    // Waits for the dump of a frame at least `request`.
    bool waitForFrame(int request) {
        return waitUntil(
            [&] {
                return err().find("view: frame " + std::to_string(request) + " written") !=
                       std::string::npos;
            },
            8s);
    }
    bool waitForText(const std::string& text) {
        return waitUntil([&] { return err().find(text) != std::string::npos; }, 8s);
    }
    Image reference() {
        const RunResult r = runCsgray({"render", part_.string(), "--size",
                                       std::to_string(kWidth) + "x" + std::to_string(kHeight), "-o",
                                       (dir_ / "ref.png").string(), "--quiet"},
                                      dir_.path());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readPng(dir_ / "ref.png");
    }
    // xdotool with the view's window as %1 (it searches by the title's prefix).
    int xdotool(const std::string& actions) {
        const std::string command =
            "DISPLAY=" + display_->name() +
            " xdotool search --sync --onlyvisible --name '^csgray view|error' " + actions +
            " >>xdotool.txt 2>&1";
        return std::system(("cd " + shellQuote(dir_.path().string()) + " && " + command).c_str());
    }
    int exitStatus(std::chrono::milliseconds timeout) {
        int status = 0;
        if (!waitUntil([&] { return ::waitpid(pid_, &status, WNOHANG) == pid_; }, timeout))
            return -1;
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

    static VirtualDisplay* display_;
    ScratchDir dir_;
    fs::path part_;
    pid_t pid_ = -1;
};

VirtualDisplay* ViewerTest::display_ = nullptr;

// No X server needed: without any display SDL would fall back to its offscreen driver, a
// window nobody sees in a viewer that never ends. The view says so and exits 3 instead.
TEST(ViewerWithoutDisplay, SaysSoAndExitsWithThree) {
    ScratchDir dir;
    writeFile(dir / "part.scad", kPart);
    const pid_t pid = spawn("exec env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER " +
                                shellQuote(CSGRAY_EXE) + " view part.scad 2>stderr.txt",
                            dir.path());
    int status = 0;
    const bool exited = waitUntil([&] { return ::waitpid(pid, &status, WNOHANG) == pid; }, 10s);
    if (!exited) {
        ::kill(-pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
    }
    ASSERT_TRUE(exited) << "the view kept running with no display";
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 3);
    EXPECT_NE(readFile(dir / "stderr.txt").find("cannot open a window: no display"),
              std::string::npos)
        << readFile(dir / "stderr.txt");
}

// A part that cannot be read is an I/O failure, exit 3 as for the other commands, found before
// any window is needed.
TEST(ViewerWithoutDisplay, UnreadablePartExitsWithThree) {
    ScratchDir dir;
    const RunResult r = runCsgray({"view", "missing.scad"}, dir.path());
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("missing.scad: error: cannot open the part"), std::string::npos) << r.err;
}

// `csgray view` loads SDL at run time (viewer/window/SdlLibrary.h) so that the other commands
// do not load its ~45 libraries. A machine without it gets a message naming the library and
// the Debian package, not a crash.
TEST(SdlLoader, MissingLibraryNamesItAndThePackage) {
    viewer::window::SdlFunctions table;
    const std::string error = viewer::window::loadSdlFunctions("libcsgray-no-such-sdl.so.0", table);
    EXPECT_NE(error.find("cannot load libcsgray-no-such-sdl.so.0"), std::string::npos) << error;
    EXPECT_NE(error.find("libsdl2-2.0-0"), std::string::npos) << error;
    EXPECT_EQ(table.SDL_Init, nullptr);
}

// A library that loads but is not SDL (libm): the first function it lacks is named.
TEST(SdlLoader, LibraryWithoutTheFunctionsNamesTheMissingOne) {
    viewer::window::SdlFunctions table;
    const std::string error = viewer::window::loadSdlFunctions("libm.so.6", table);
    EXPECT_NE(error.find("libm.so.6: it has no SDL_"), std::string::npos) << error;
    EXPECT_NE(error.find("libsdl2-2.0-0"), std::string::npos) << error;
    EXPECT_EQ(table.SDL_Init, nullptr);
}

TEST(SdlLoader, InstalledSdlHasEveryFunctionTheViewerCalls) {
    viewer::window::SdlFunctions table;
    const std::string error =
        viewer::window::loadSdlFunctions(viewer::window::kSdlLibraryName, table);
    ASSERT_EQ(error, "");
#define CSGRAY_SDL_EXPECT_SET(name) EXPECT_NE(table.name, nullptr) << #name;
    CSGRAY_SDL_FUNCTIONS(CSGRAY_SDL_EXPECT_SET)
#undef CSGRAY_SDL_EXPECT_SET
}

// The point of loading SDL at run time: csgray itself does not link it (nor X11 through it).
TEST(SdlLoader, CsgrayDoesNotLinkSdl) {
    FILE* pipe = ::popen(("ldd " + shellQuote(CSGRAY_EXE) + " 2>&1").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string libraries;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) libraries += buffer;
    ASSERT_EQ(::pclose(pipe), 0) << libraries;
    EXPECT_NE(libraries.find("libc.so"), std::string::npos) << libraries;
    EXPECT_EQ(libraries.find("libSDL2"), std::string::npos) << libraries;
    EXPECT_EQ(libraries.find("libX11"), std::string::npos) << libraries;
}

TEST_F(ViewerTest, FinestFrameShowsThePartAsRenderDoes) {
    launch();
    ASSERT_TRUE(waitForFrame(1)) << err();
    const Image frame = readPng(dir_ / "frame.png");
    ASSERT_EQ(frame.width, kWidth);
    EXPECT_GT(coverage(frame), 0.05) << "the part is not visible";
    EXPECT_LE(maxDifference(frame, reference()), 2);
    EXPECT_NE(err().find("view: first frame ("), std::string::npos) << err();
}

TEST_F(ViewerTest, KeysAndClickReachTheWindow) {
    if (!onPath("xdotool")) SKIP_OR_FAIL_IN_CI("xdotool is not installed (Debian package xdotool)");
    launch();
    ASSERT_TRUE(waitForFrame(1)) << err();
    const Image first = readPng(dir_ / "frame.png");

    // A click on the part prints the probe JSON of that ray and a summary.
    ASSERT_EQ(xdotool("windowfocus %1 mousemove --window %1 80 60 click 1"), 0);
    ASSERT_TRUE(waitForText("view: probe: ")) << err();
    EXPECT_NE(err().find("{\"ray\":{\"origin\""), std::string::npos) << err();
    EXPECT_NE(err().find("part.scad:"), std::string::npos) << "no source line in the probe";
    // The panel lists the spans with their objects and source lines.
    EXPECT_TRUE(waitForPanel([](const std::string& p) {
        return has(p, "probe: probe at pixel 80,60: ") && has(p, "probe: span 1: t ") &&
               has(p, "part.scad:") && has(p, "probe:       | ");
    })) << panel();

    // O switches to orthographic: a new, different finest frame.
    ASSERT_EQ(xdotool("windowfocus %1 key o"), 0);
    ASSERT_TRUE(waitForFrame(2)) << err();
    EXPECT_GT(maxDifference(readPng(dir_ / "frame.png"), first), 16);

    // P saves a screenshot, named on stderr.
    ASSERT_EQ(xdotool("windowfocus %1 key p"), 0);
    ASSERT_TRUE(waitForText("view: screenshot saved to csgray-view-part-001.png")) << err();
    // The picture alone: the panel drawn over it is not saved.
    EXPECT_EQ(maxDifference(readPng(dir_ / "csgray-view-part-001.png"), frame()), 0);

    // H hides the panel and shows it again.
    ASSERT_EQ(xdotool("windowfocus %1 key h"), 0);
    EXPECT_TRUE(waitForPanel([](const std::string& p) { return has(p, "visible: no"); }))
        << panel();
    ASSERT_EQ(xdotool("windowfocus %1 key h"), 0);
    EXPECT_TRUE(waitForPanel([](const std::string& p) { return has(p, "visible: yes"); }))
        << panel();

    // The window closes on the key press, so xdotool's key release may find no window: its
    // status says nothing here; the view's exit status does.
    xdotool("windowfocus %1 key q");
    EXPECT_EQ(exitStatus(5s), 0) << err();
}

TEST_F(ViewerTest, EditReloadsAndSyntaxErrorKeepsTheLastGoodFrame) {
    launch();
    ASSERT_TRUE(waitForFrame(1)) << err();
    const Image first = readPng(dir_ / "frame.png");

    // A bigger sphere: the reload renders a different frame.
    std::string edited = kPart;
    edited.replace(edited.find("r = 4"), 5, "r = 7");
    writeFile(part_, edited);
    ASSERT_TRUE(waitForText("view: reloaded part.scad")) << err();
    ASSERT_TRUE(waitForFrame(2)) << err();
    const Image second = readPng(dir_ / "frame.png");
    EXPECT_GT(maxDifference(second, first), 16);

    // A syntax error on line 3: reported with file:line:col, and no new frame replaces the
    // last good one.
    writeFile(part_, "cube(5);\nsphere(2);\ncube([1, 2;\n");
    ASSERT_TRUE(waitForText("view: reload failed")) << err();
    EXPECT_NE(err().find("part.scad:3:"), std::string::npos) << err();
    EXPECT_NE(err().find(": error: "), std::string::npos) << err();
    // The window shows it too, over the last good picture.
    EXPECT_TRUE(waitForPanel([](const std::string& p) {
        return has(p, "visible: yes\nerror: part.scad:3:") && has(p, ": error: ");
    })) << panel();
    EXPECT_EQ(maxDifference(readPng(dir_ / "frame.png"), second), 0);

    // Fixing the file brings the window back. No frame was written while the file was broken:
    // the view's log (one stream, in order) has no frame between the failed reload and the
    // next good one, and the fixed file's frame is number 3. An ordering in the log, not an
    // absence after a sleep, so a slow machine cannot pass a frame that came late.
    writeFile(part_, kPart);
    ASSERT_TRUE(waitForFrame(3)) << err();
    {
        const std::string log = err();
        const size_t failed = log.find("view: reload failed");
        const size_t fixed = log.find("view: reloaded part.scad", failed);
        ASSERT_NE(fixed, std::string::npos) << log;
        EXPECT_EQ(log.substr(failed, fixed - failed).find("view: frame"), std::string::npos) << log;
        EXPECT_GT(log.find("view: frame 3 written"), fixed) << log;
    }
    EXPECT_LE(maxDifference(readPng(dir_ / "frame.png"), first), 2);
    EXPECT_TRUE(waitForPanel([](const std::string& p) { return !has(p, "error:"); })) << panel();
}

// An edit that includes a new, broken file: the file the error names was never read by a good
// load, yet fixing it alone (the part itself unchanged) reloads the view.
TEST_F(ViewerTest, FixingTheFileAnErrorNamesReloads) {
    launch();
    ASSERT_TRUE(waitForFrame(1)) << err();
    writeFile(dir_ / "extra.scad", "translate([0, -12, 0]) sphere(r = 3;\n");
    writeFile(part_, std::string(kPart) + "include <extra.scad>\n");
    ASSERT_TRUE(waitForText("view: reload failed")) << err();
    EXPECT_NE(err().find("extra.scad:1:"), std::string::npos) << err();

    writeFile(dir_ / "extra.scad", "translate([0, -12, 0]) sphere(r = 3);\n");
    ASSERT_TRUE(waitForText("view: reloaded part.scad")) << err();
    ASSERT_TRUE(waitForFrame(2)) << err();
}

TEST_F(ViewerTest, DragOrbitsWheelZoomsAndResetAndFrameRestoreTheView) {
    if (!onPath("xdotool")) SKIP_OR_FAIL_IN_CI("xdotool is not installed (Debian package xdotool)");
    launch();
    ASSERT_TRUE(waitForFrame(1)) << err();
    const Image first = frame();

    // A 40-pixel left drag (one motion event) turns the part: request 2, a different picture,
    // and no probe (a drag is not a click).
    ASSERT_EQ(xdotool("windowfocus %1 mousemove --window %1 60 60 mousedown 1 "
                      "mousemove --window %1 100 60 mouseup 1"),
              0);
    ASSERT_TRUE(waitForFrame(2)) << err();
    EXPECT_GT(maxDifference(frame(), first), 16);
    EXPECT_EQ(err().find("view: probe: "), std::string::npos) << err();

    // R: the initial view again (request 3).
    ASSERT_EQ(xdotool("windowfocus %1 key r"), 0);
    ASSERT_TRUE(waitForFrame(3)) << err();
    EXPECT_LE(maxDifference(frame(), first), 2);

    // Two wheel steps towards the part (requests 4 and 5): it fills more of the window.
    ASSERT_EQ(xdotool("windowfocus %1 mousemove --window %1 80 60 click --repeat 2 4"), 0);
    ASSERT_TRUE(waitForFrame(5)) << err();
    EXPECT_GT(coverage(frame()), coverage(first) + 0.05);

    // F fits the part again from the same direction: the initial framing (request 6).
    ASSERT_EQ(xdotool("windowfocus %1 key f"), 0);
    ASSERT_TRUE(waitForFrame(6)) << err();
    EXPECT_LE(maxDifference(frame(), first), 2);
}

// The mean column and row of the pixels that differ from the background (top-left) pixel.
std::pair<double, double> centroid(const Image& image) {
    double sx = 0.0, sy = 0.0;
    size_t n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const size_t i = (size_t(y) * image.width + x) * 3;
            for (int c = 0; c < 3; ++c)
                if (std::abs(image.rgb[i + c] - image.rgb[c]) > 8) {
                    sx += x, sy += y, ++n;
                    break;
                }
        }
    return n == 0 ? std::pair{0.0, 0.0} : std::pair{sx / double(n), sy / double(n)};
}

// The claims of `csgray view --help` no other test checks: -D reaches the view's part;
// "progressively: one ray per 8x8 pixels first, then 4x4, 2x2 and every pixel" (--verbose
// prints each level shown: coarse to fine, each with ceil(size / block) rays a side; a level
// that finished before the window could show it may be skipped, so only the order and the
// sizes are held, and the last level is every pixel); a right drag pans (the picture moves
// with the pointer, where an orbit of this centred part would leave its centroid in place);
// Esc quits with status 0.
TEST_F(ViewerTest, DefineProgressiveLevelsPanAndEscape) {
    if (!onPath("xdotool")) SKIP_OR_FAIL_IN_CI("xdotool is not installed (Debian package xdotool)");
    writeFile(part_,
              "s = 1;\nassert(s == 7, \"-D did not reach the part\");\n"
              "cube(s, center = true);\n");
    launch("-D s=7");
    ASSERT_TRUE(waitForFrame(1)) << err();
    EXPECT_EQ(err().find("error"), std::string::npos) << err();
    const std::string log = err();
    int last = 16;
    for (size_t at = log.find("view: level "); at < log.find("view: frame 1 written");
         at = log.find("view: level ", at + 1)) {
        int block = 0, w = 0, h = 0;
        ASSERT_EQ(std::sscanf(log.c_str() + at, "view: level %dx%*d: %d x %d rays", &block, &w, &h),
                  3)
            << log;
        EXPECT_TRUE(block == 8 || block == 4 || block == 2 || block == 1) << block;
        EXPECT_LT(block, last) << log;
        EXPECT_EQ(w, (kWidth + block - 1) / block) << log;
        EXPECT_EQ(h, (kHeight + block - 1) / block) << log;
        last = block;
    }
    EXPECT_EQ(last, 1) << log;
    const Image first = frame();

    // A 30-pixel right drag to the right: request 2, the part moved right, not turned.
    ASSERT_EQ(xdotool("windowfocus %1 mousemove --window %1 60 60 mousedown 3 "
                      "mousemove --window %1 90 60 mouseup 3"),
              0);
    ASSERT_TRUE(waitForFrame(2)) << err();
    const auto [x0, y0] = centroid(first);
    const auto [x1, y1] = centroid(frame());
    EXPECT_GT(x1 - x0, 10.0) << x0 << " -> " << x1;
    EXPECT_LT(std::abs(y1 - y0), 3.0) << y0 << " -> " << y1;
    EXPECT_EQ(err().find("view: probe: "), std::string::npos) << err();

    xdotool("windowfocus %1 key Escape");  // the window closes on the press: see Q above
    EXPECT_EQ(exitStatus(5s), 0) << err();
}

TEST_F(ViewerTest, EffectKeysSwitchShadowsReflectionAndRefraction) {
    if (!onPath("xdotool")) SKIP_OR_FAIL_IN_CI("xdotool is not installed (Debian package xdotool)");
    writeFile(part_, kEffectsPart);
    launch();
    ASSERT_TRUE(waitForFrame(1)) << err();
    ASSERT_TRUE(waitForPanel([](const std::string& p) {
        return has(p, "status: 1x1 level") && has(p, "shadows reflection refraction");
    })) << panel();
    Image previous = frame();

    // Each key switches its effect off: the next request's plan says so and the picture
    // changes.
    struct Step {
        const char* key;
        int request;
        const char* off;
    };
    for (const Step& step :
         {Step{"s", 2, "shadows"}, Step{"m", 3, "reflection"}, Step{"t", 4, "refraction"}}) {
        SCOPED_TRACE(step.key);
        ASSERT_EQ(xdotool(std::string("windowfocus %1 key ") + step.key), 0);
        ASSERT_TRUE(waitForFrame(step.request)) << err();
        EXPECT_TRUE(waitForPanel([&](const std::string& p) {
            return has(p, "status: 1x1 level") && !has(p, step.off);
        })) << panel();
        const Image current = frame();
        EXPECT_GT(maxDifference(current, previous), 16);
        previous = current;
    }
    // S again: shadows are back.
    ASSERT_EQ(xdotool("windowfocus %1 key s"), 0);
    ASSERT_TRUE(waitForFrame(5)) << err();
    EXPECT_TRUE(waitForPanel([](const std::string& p) {
        return has(p, "status: 1x1 level") && has(p, "shadows") && !has(p, "reflection");
    })) << panel();
}

}  // namespace
