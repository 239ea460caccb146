#include "viewer/cli/ViewCommand.h"

#include <time.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <thread>

#include "primitives/base/AtomicFile.h"
#include "primitives/base/ParallelFor.h"
#include "viewer/cli/Cli.h"
#include "viewer/render/RenderCamera.h"
#include "viewer/window/PartWatcher.h"
#include "viewer/window/ProgressiveRenderer.h"
#include "viewer/window/Screenshot.h"
#include "viewer/window/SdlLibrary.h"
#include "viewer/window/ViewCamera.h"
#include "viewer/window/ViewProbe.h"
#include "viewer/window/ViewWindow.h"

namespace viewer::window {

namespace {

const char* const kViewHelp =
    "usage: csgray view PART [options]\n"
    "\n"
    "Opens a window that ray traces the part with the renderer of `csgray render`,\n"
    "progressively: one ray per 8x8 pixels first, then 4x4, 2x2 and every pixel, refined\n"
    "while the view is still and restarted when it moves. The part is reloaded when it or a\n"
    "file it includes changes; an error keeps the last good part on screen, shows the\n"
    "error at the top of the window with a red border, and prints it on stderr. A panel\n"
    "over the picture shows the status (level, rays per second, effects) at the bottom and\n"
    "the last probe at the top left; screenshots never include it.\n"
    "\n"
    "mouse:  left drag orbit, right or middle drag pan, wheel zoom,\n"
    "        left click probe the ray under the pointer (JSON as `csgray probe`, on stderr)\n"
    "keys:   R reset view, F frame the part, O orthographic/perspective,\n"
    "        S shadows, M reflection, T refraction (on/off), P save a screenshot PNG\n"
    "        (named on stderr, without the panel), H hide/show the panel, Q or Esc quit\n"
    "\n"
    "options:\n"
    "  --size WxH             window size in pixels (default 800x600)\n"
    "  --threads N            rendering threads (default: all cores)\n"
    "  --verbose              print each refinement level's time and ray rate on stderr\n"
    "\n"
    "environment:\n"
    "  CSGRAY_VIEW_DUMP=FILE  (for tests) write every finished full-resolution frame to\n"
    "                         FILE as PNG and say so on stderr, and the panel's text to\n"
    "                         FILE.panel.txt whenever the window shows a changed panel\n";

struct ViewOptions {
    CommonOptions common;
    int width = 800, height = 600;
    int threads = 0;  // 0: all cores
    bool verbose = false;
};

ViewOptions parseViewOptions(std::span<const std::string> args) {
    ViewOptions o;
    ArgCursor cursor(args);
    while (!cursor.done()) {
        if (auto size = cursor.option("--size")) {
            std::tie(o.width, o.height) = parseSize(*size, "--size");
        } else if (auto threads = cursor.option("--threads")) {
            o.threads = parsePositiveInt(*threads, "--threads", 1024);
        } else if (cursor.flag("--verbose") || cursor.flag("-v")) {
            o.verbose = true;
        } else if (!cursor.common(o.common)) {
            throw UsageError("view: unknown option '" + cursor.peek() + "'");
        }
    }
    if (!o.common.help) requirePart(o.common, "view");
    return o;
}

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string formatRate(double raysPerSecond) {
    char text[32];
    if (raysPerSecond >= 1e6)
        std::snprintf(text, sizeof text, "%.2f Mrays/s", raysPerSecond / 1e6);
    else
        std::snprintf(text, sizeof text, "%.0f krays/s", raysPerSecond / 1e3);
    return text;
}

// Everything the event loop changes, and what it shows.
class ViewSession {
public:
    ViewSession(const ViewOptions& options, Clock::time_point started)
        : options_(options),
          started_(started),
          width_(options.width),
          height_(options.height),
          wakeEvent_(sdl().SDL_RegisterEvents(1)),
          renderer_(csg::resolveThreads(options.threads), [this] { wake(); }),
          watcher_(options.common, [this] { wake(); }) {
        if (const char* dump = std::getenv("CSGRAY_VIEW_DUMP")) dumpFile_ = dump;
    }

    // The first load, and the first render request when it succeeds. Needs no window: it
    // runs while SDL starts. Else loadPart's exit code (diagnostics printed).
    int begin() {
        LoadOutcome first = loadForView(options_.common);
        if (!first.part) return first.exitCode;
        if (options_.verbose)
            std::fprintf(stderr, "view: loaded and compiled in %.1f ms, %.1f ms after main\n",
                         first.seconds * 1e3, millisecondsSince(started_));
        part_ = std::move(first.part);
        camera_.emplace(initialCamera());
        watcher_.watch(filesRead(part_->model));
        renderer_.hold();
        restart();
        return kExitOk;
    }

    // The event loop, after begin() succeeded. Returns the exit code.
    int run(ViewWindow& window) {
        window_ = &window;
        wakeReady_ = true;
        renderer_.release();
        Clock::time_point lastPoll = Clock::now();
        while (!quit_) {
            // What is ready is shown before waiting: the first levels may have finished while
            // the window was being made.
            if (auto outcome = watcher_.take()) reloaded(std::move(*outcome));
            if (auto frame = renderer_.take()) shown(std::move(*frame));
            if (restartPending_) restart();
            if (redraw_) {
                window_->setPanel(panel_);
                window_->present();
                dumpPanel();
                redraw_ = false;
                reportFirstFrame();
            }
            SDL_Event event;
            if (sdl().SDL_WaitEventTimeout(&event, 50)) {
                handle(event);
                while (sdl().SDL_PollEvent(&event)) handle(event);
            }
            // Hot reload: four polls a second cost a few stat() calls.
            if (millisecondsSince(lastPoll) >= 250.0) {
                watcher_.poll();
                lastPoll = Clock::now();
            }
        }
        return kExitOk;
    }

private:
    // Wakes SDL_WaitEventTimeout from another thread (SDL_PushEvent is thread-safe). Before
    // run() there is no event loop to wake (and SDL may still be starting): run() looks first.
    void wake() {
        if (!wakeReady_) return;
        SDL_Event event{};
        event.type = wakeEvent_;
        sdl().SDL_PushEvent(&event);
    }

    render::Camera initialCamera() const {
        // Exactly what `csgray render --size WxH` uses, so the finest level matches it.
        return part_->model.camera ? *part_->model.camera
                                   : render::frameBounds(part_->scene, aspect());
    }
    double aspect() const { return double(width_) / double(height_); }

    void restart() {
        restartPending_ = false;
        RenderRequest request;
        request.part = part_;
        request.camera = camera_->camera();
        request.width = width_;
        request.height = height_;
        request.effects = effects_;
        renderer_.start(std::move(request));
    }

    void handle(const SDL_Event& event) {
        switch (event.type) {
            case SDL_QUIT:
                quit_ = true;
                break;
            case SDL_KEYDOWN:
                key(event.key.keysym.sym);
                break;
            case SDL_MOUSEBUTTONDOWN:
                dragButton_ = event.button.button;
                dragDistance_ = 0.0;
                break;
            case SDL_MOUSEBUTTONUP:
                if (event.button.button == SDL_BUTTON_LEFT && dragButton_ == SDL_BUTTON_LEFT &&
                    dragDistance_ < 3.0)
                    probe(event.button.x, event.button.y);
                dragButton_ = 0;
                break;
            case SDL_MOUSEMOTION:
                drag(event.motion);
                break;
            case SDL_MOUSEWHEEL:
                camera_->zoom(event.wheel.preciseY != 0.0f ? event.wheel.preciseY
                                                           : float(event.wheel.y));
                restartPending_ = true;
                break;
            case SDL_WINDOWEVENT:
                // Only a real change restarts: a window manager may repeat the size.
                if (event.window.event == SDL_WINDOWEVENT_SIZE_CHANGED &&
                    (event.window.data1 != width_ || event.window.data2 != height_)) {
                    width_ = std::max(event.window.data1, 1);
                    height_ = std::max(event.window.data2, 1);
                    restartPending_ = true;
                }
                redraw_ = true;
                break;
            default:
                break;
        }
    }

    void drag(const SDL_MouseMotionEvent& motion) {
        if (dragButton_ == 0) return;
        dragDistance_ += std::abs(motion.xrel) + std::abs(motion.yrel);
        // Below a few pixels it is still a click (a probe), not a drag.
        if (dragDistance_ < 3.0) return;
        if (dragButton_ == SDL_BUTTON_LEFT)
            camera_->orbit(motion.xrel, motion.yrel, height_);
        else
            camera_->pan(motion.xrel, motion.yrel, height_);
        restartPending_ = true;
    }

    void key(SDL_Keycode key) {
        switch (key) {
            case SDLK_q:
            case SDLK_ESCAPE:
                quit_ = true;
                return;
            case SDLK_r:
                camera_->reset();
                break;
            case SDLK_f:
                camera_->frame(part_->scene, aspect());
                break;
            case SDLK_o:
                camera_->toggleOrthographic();
                break;
            case SDLK_s:
                effects_.shadows = !effects_.shadows;
                break;
            case SDLK_m:
                effects_.reflection = !effects_.reflection;
                break;
            case SDLK_t:
                effects_.refraction = !effects_.refraction;
                break;
            case SDLK_p:
                screenshot();
                return;
            case SDLK_h:
                panel_.visible = !panel_.visible;
                redraw_ = true;
                return;
            default:
                return;
        }
        restartPending_ = true;
    }

    void probe(int x, int y) {
        const PixelProbe result = probePixel(*part_, camera_->camera(), width_, height_, x, y);
        std::fprintf(stderr, "%s\n", result.json.c_str());
        std::fprintf(stderr, "view: %s (pixel %d,%d)\n", result.summary.c_str(), x, y);
        probeSummary_ = result.summary;
        panel_.probe = result.lines;
        updateTitle();
    }

    void screenshot() {
        if (!lastFrame_) {
            std::fprintf(stderr, "view: no frame to save yet\n");
            return;
        }
        const std::string name = nextScreenshotName(options_.common.part);
        const std::string error =
            render::writePng(name, upscaleNearest(lastFrame_->image, width_, height_));
        if (error.empty())
            std::fprintf(stderr, "view: screenshot saved to %s\n", name.c_str());
        else
            std::fprintf(stderr, "%s: error: %s\n", name.c_str(), error.c_str());
    }

    void reloaded(LoadOutcome outcome) {
        if (!outcome.part) {
            loadError_ = outcome.firstError;
            std::fprintf(stderr, "view: reload failed; the last good part stays on screen\n");
            std::vector<std::string> files = filesRead(part_->model);
            files.insert(files.end(), outcome.namedFiles.begin(), outcome.namedFiles.end());
            watcher_.watch(files);
            window_->setErrorBorder(true);
            updateTitle();
            redraw_ = true;
            return;
        }
        std::fprintf(stderr, "view: reloaded %s in %.1f ms\n", options_.common.part.c_str(),
                     outcome.seconds * 1e3);
        part_ = std::move(outcome.part);
        loadError_.clear();
        window_->setErrorBorder(false);
        updateTitle();
        camera_->setInitial(initialCamera());
        watcher_.watch(filesRead(part_->model));
        restart();
        redraw_ = true;
    }

    void shown(ProgressiveFrame frame) {
        window_->setImage(frame.image);
        redraw_ = true;
        const double rate = frame.rays.total() / std::max(frame.renderSeconds, 1e-9);
        status_ = std::to_string(frame.blockSize) + "x" + std::to_string(frame.blockSize) +
                  " level, " + formatRate(rate) + ", " + frame.plan;
        if (!firstFrame_) firstFrame_ = FirstFrame{frame.blockSize, frame.sinceRequest};
        if (options_.verbose)
            std::fprintf(stderr,
                         "view: level %dx%d: %d x %d rays in %.1f ms (%s), %.1f ms "
                         "after the request\n",
                         frame.blockSize, frame.blockSize, frame.image.width, frame.image.height,
                         frame.renderSeconds * 1e3, formatRate(rate).c_str(),
                         frame.sinceRequest * 1e3);
        if (frame.blockSize == 1 && !dumpFile_.empty()) {
            const std::string error = render::writePng(dumpFile_, frame.image);
            if (error.empty())
                std::fprintf(stderr, "view: frame %llu written to %s\n",
                             (unsigned long long)frame.request, dumpFile_.c_str());
            else
                std::fprintf(stderr, "%s: error: %s\n", dumpFile_.c_str(), error.c_str());
        }
        lastFrame_ = std::move(frame);
        updateTitle();
    }

    // The title bar and the panel say the same: error, status, probe.
    void updateTitle() {
        std::string status = status_;
        if (camera_->camera().projection == render::Projection::Orthographic) status += ", ortho";
        std::string title = "csgray view " + options_.common.part;
        if (!loadError_.empty()) title = loadError_ + "  |  " + title;
        if (!status_.empty()) title += "  |  " + status;
        if (!probeSummary_.empty()) title += "  |  " + probeSummary_;
        window_->setTitle(title);
        panel_.error = loadError_;
        panel_.status = status;
        redraw_ = true;
    }

    // Once, when the first frame is on screen. The wall-clock time lets a launcher measure
    // from before the process existed (bench/view_startup.py).
    void reportFirstFrame() {
        if (!firstFrame_ || firstFrameReported_) return;
        firstFrameReported_ = true;
        const double wall =
            std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                .count();
        std::fprintf(stderr,
                     "view: first frame (%dx%d blocks) presented at %.6f s, %.1f ms after the "
                     "render started, %.1f ms after main\n",
                     firstFrame_->blockSize, firstFrame_->blockSize, wall,
                     firstFrame_->sinceRequest * 1e3, millisecondsSince(started_));
    }

    // The test hook's view of the panel: what the window shows, written when it changes.
    void dumpPanel() {
        if (dumpFile_.empty() || panel_ == dumpedPanel_) return;
        dumpedPanel_ = panel_;
        const std::string error =
            csg::writeFileAtomically(dumpFile_ + ".panel.txt", panelText(panel_));
        if (!error.empty())
            std::fprintf(stderr, "%s.panel.txt: error: %s\n", dumpFile_.c_str(), error.c_str());
    }

    const ViewOptions& options_;
    ViewWindow* window_ = nullptr;  // set by run()
    std::atomic<bool> wakeReady_{false};
    Clock::time_point started_;
    int width_, height_;
    Uint32 wakeEvent_;
    std::shared_ptr<const LoadedPart> part_;
    std::optional<ViewCamera> camera_;
    EffectToggles effects_;
    bool restartPending_ = false, redraw_ = false, quit_ = false;
    Uint8 dragButton_ = 0;
    double dragDistance_ = 0.0;
    std::optional<ProgressiveFrame> lastFrame_;
    struct FirstFrame {
        int blockSize;
        double sinceRequest;  // seconds
    };
    std::optional<FirstFrame> firstFrame_;
    bool firstFrameReported_ = false;
    std::string status_, loadError_, probeSummary_, dumpFile_;
    Panel panel_, dumpedPanel_;
    // Last: their threads call wake(), so they stop before the rest is destroyed.
    ProgressiveRenderer renderer_;
    PartWatcher watcher_;
};

}  // namespace

int viewCommand(std::span<const std::string> args) {
    const Clock::time_point started = Clock::now();
    // The process's CPU time so far: exec, dynamic loading and static initialisation, which
    // no clock inside the program sees start (SDL and the X11 libraries come later: loadSdl).
    timespec cpuNow{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpuNow);
    const double cpuBeforeMain = double(cpuNow.tv_sec) * 1e3 + double(cpuNow.tv_nsec) * 1e-6;
    const ViewOptions options = parseViewOptions(args);
    if (options.common.help) {
        std::fputs(kViewHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    // SDL is loaded here, not linked (see SdlLibrary.h); without it there is no window.
    if (const std::string& sdlError = loadSdl(); !sdlError.empty()) {
        std::fprintf(stderr, "csgray: error: %s\n", sdlError.c_str());
        return kExitIo;
    }
    // Start-up in parallel: SDL's video start (tens of milliseconds of X11 set-up) on this
    // thread, the part's evaluation, compilation and first coarse levels on others. The
    // window itself is made only once the part loaded: a bad part exits with no window.
    ViewWindow::prepareProcess();
    std::optional<ViewWindow> window;  // outlives the session, whose threads wake its loop
    ViewSession session(options, started);
    int loaded = kExitOk;
    std::thread loader([&] { loaded = session.begin(); });
    window.emplace();
    loader.join();
    // The first load decides whether there is anything to show; later errors keep it.
    if (loaded != kExitOk) return loaded;
    if (window->ok())
        window->open("csgray view " + options.common.part, options.width, options.height);
    if (!window->ok()) {
        std::fprintf(stderr, "csgray: error: %s\n", window->error().c_str());
        return kExitIo;
    }
    if (options.verbose) {
        const ViewWindow::StartupTimes& t = window->startupTimes();
        std::fprintf(stderr,
                     "view: startup: SDL_Init %.1f ms (%.1f ms CPU), window %.1f ms, renderer "
                     "%.1f ms (%s); %.1f ms after main, which started after %.1f ms of CPU\n",
                     t.init, t.initCpu, t.window, t.renderer, t.driver.c_str(),
                     millisecondsSince(started), cpuBeforeMain);
    }
    const int code = session.run(*window);
    // Leave without tearing SDL down. A worker's wake() may have just sent the window an X
    // ClientMessage (SDL_PushEvent does so on SDL's second X connection) that the X server has
    // not processed yet; if SDL_DestroyWindow's request on the first connection is served
    // first, the message fails with BadWindow and Xlib's default handler exits with status 1
    // (seen in about 1 of 35 quits under load). At process exit the server drops the window
    // and such an error has no one to reach.
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(code);
}

}  // namespace viewer::window
