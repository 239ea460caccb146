#include "viewer/window/ViewWindow.h"

#include <stdlib.h>
#include <time.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "viewer/window/SdlLibrary.h"

namespace viewer::window {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// CPU time of the calling thread: on a loaded machine, what a step costs, whatever it waited.
double threadCpuMilliseconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

}  // namespace

void ViewWindow::prepareProcess() {
    // SDL opens an X input method for text input, and Xlib then parses the locale's whole
    // Compose table (en_US.UTF-8: thousands of lines), most of SDL_Init's CPU (bench/README.md,
    // csgray view).
    // The window reads keys, never composed text, so an empty table loses nothing. A
    // compose file the user chose is kept.
    setenv("XCOMPOSEFILE", "/dev/null", 0);
}

ViewWindow::ViewWindow() {
    // What the window draws is one texture stretched by nearest neighbour and a few hundred
    // rectangles: SDL's software renderer presents that quickly and is ready at once, where its
    // OpenGL renderer took longer to create under Xvfb (Mesa's llvmpipe) than the rest of the
    // start-up and compiled shaders on the first present (bench/README.md, csgray view). So:
    // software, straight to the X11 framebuffer (no GL window texture behind it).
    // SDL_RENDER_DRIVER and SDL_FRAMEBUFFER_ACCELERATION in the environment still win over
    // these hints.
    sdl().SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
    sdl().SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
    // A preview window has no reason to keep the screen awake (OpenSCAD's does not either);
    // inhibiting the screen saver also costs a D-Bus round trip at start-up.
    sdl().SDL_SetHint(SDL_HINT_VIDEO_ALLOW_SCREENSAVER, "1");
    // Blocks, not blur: a coarse level should look like what it is.
    sdl().SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "0");
    const Clock::time_point step = Clock::now();
    const double cpu = threadCpuMilliseconds();
    if (sdl().SDL_Init(SDL_INIT_VIDEO) != 0) {
        error_ = std::string("cannot open a window: ") + sdl().SDL_GetError();
        return;
    }
    videoStarted_ = true;
    // Without a display SDL falls back to its offscreen driver: a window nobody can see, and
    // a viewer that never ends. Only when asked for (SDL_VIDEODRIVER) is that a window.
    const char* driver = sdl().SDL_GetCurrentVideoDriver();
    if (driver && !std::getenv("SDL_VIDEODRIVER") &&
        (std::string(driver) == "offscreen" || std::string(driver) == "dummy")) {
        error_ = "cannot open a window: no display (neither DISPLAY nor WAYLAND_DISPLAY works)";
        return;
    }
    startup_.init = millisecondsSince(step);
    startup_.initCpu = threadCpuMilliseconds() - cpu;
}

bool ViewWindow::open(const std::string& title, int width, int height) {
    if (!videoStarted_) return false;
    Clock::time_point step = Clock::now();
    window_ = sdl().SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_UNDEFINED,
                                     SDL_WINDOWPOS_UNDEFINED, width, height, SDL_WINDOW_RESIZABLE);
    if (!window_) {
        error_ = std::string("cannot open a window: ") + sdl().SDL_GetError();
        return false;
    }
    startup_.window = millisecondsSince(step);
    step = Clock::now();
    renderer_ = sdl().SDL_CreateRenderer(window_, -1, 0);
    if (!renderer_) renderer_ = sdl().SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
    if (!renderer_) {
        error_ = std::string("cannot draw in the window: ") + sdl().SDL_GetError();
        return false;
    }
    startup_.renderer = millisecondsSince(step);
    SDL_RendererInfo info;
    if (sdl().SDL_GetRendererInfo(renderer_, &info) == 0) startup_.driver = info.name;
    if (const char* video = sdl().SDL_GetCurrentVideoDriver())
        startup_.driver += std::string(" on ") + video;
    return true;
}

ViewWindow::~ViewWindow() {
    if (texture_) sdl().SDL_DestroyTexture(texture_);
    if (renderer_) sdl().SDL_DestroyRenderer(renderer_);
    if (window_) sdl().SDL_DestroyWindow(window_);
    if (videoStarted_) sdl().SDL_Quit();
}

void ViewWindow::setImage(const render::Rgb8Image& image) {
    if (!texture_ || textureWidth_ != image.width || textureHeight_ != image.height) {
        if (texture_) sdl().SDL_DestroyTexture(texture_);
        texture_ = sdl().SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24,
                                           SDL_TEXTUREACCESS_STREAMING, image.width, image.height);
        textureWidth_ = image.width;
        textureHeight_ = image.height;
    }
    if (texture_) sdl().SDL_UpdateTexture(texture_, nullptr, image.pixels.data(), image.width * 3);
}

void ViewWindow::setTitle(const std::string& title) {
    sdl().SDL_SetWindowTitle(window_, title.c_str());
}

void ViewWindow::present() {
    sdl().SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
    sdl().SDL_RenderClear(renderer_);
    if (texture_) sdl().SDL_RenderCopy(renderer_, texture_, nullptr, nullptr);
    if (errorBorder_) {
        int w = 0, h = 0;
        sdl().SDL_GetRendererOutputSize(renderer_, &w, &h);
        const int b = 6;  // pixels: visible, yet hides little of the part
        const SDL_Rect sides[] = {{0, 0, w, b}, {0, h - b, w, b}, {0, 0, b, h}, {w - b, 0, b, h}};
        sdl().SDL_SetRenderDrawColor(renderer_, 220, 30, 30, 255);
        sdl().SDL_RenderFillRects(renderer_, sides, 4);
    }
    painter_.draw(renderer_, panel_);
    sdl().SDL_RenderPresent(renderer_);
}

}  // namespace viewer::window
