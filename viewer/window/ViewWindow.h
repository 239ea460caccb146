// The SDL2 side of `csgray view`: one window, its renderer and one streaming texture that
// holds the latest refinement level. The texture has the level's size and is stretched to the
// window with nearest-neighbour sampling, which is what shows a coarse level as blocks.
// Status, errors and the probe are drawn over it by the panel (PanelDrawing.h) and repeated in
// the title bar; an error also draws a red border. Neither is ever part of the picture.
#pragma once

#include <string>

#include "viewer/render/PngWriter.h"
#include "viewer/window/Panel.h"
#include "viewer/window/PanelDrawing.h"

struct SDL_Window;
struct SDL_Renderer;
struct SDL_Texture;

namespace viewer::window {

class ViewWindow {
public:
    // Starts SDL's video (the slow part: the X connection, keyboard and input method), so it
    // can run while the part loads; open() then makes the window. ok() is false (and error()
    // says why) when no display is usable.
    ViewWindow();
    // Call once before the process starts any thread (it sets environment variables, which is
    // not thread-safe): makes SDL's X11 start-up skip work the window does not need.
    static void prepareProcess();
    // Opens the window with SDL's software renderer (see ViewWindow.cpp for why). Returns ok().
    bool open(const std::string& title, int width, int height);
    ~ViewWindow();
    ViewWindow(const ViewWindow&) = delete;
    ViewWindow& operator=(const ViewWindow&) = delete;

    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }
    // What start-up cost, for --verbose: milliseconds of each step and the SDL render driver.
    struct StartupTimes {
        double init = 0.0, window = 0.0, renderer = 0.0;
        double initCpu = 0.0;  // the thread's CPU time in SDL_Init
        std::string driver;
    };
    const StartupTimes& startupTimes() const { return startup_; }

    // Replaces the picture (any size; stretched to the window when drawn).
    void setImage(const render::Rgb8Image& image);
    void setTitle(const std::string& title);
    // A red frame around the picture: the part on screen is not what the file says.
    void setErrorBorder(bool on) { errorBorder_ = on; }
    // What the panel over the picture says from the next present() on.
    void setPanel(const Panel& panel) { panel_ = panel; }
    // Draws the picture, the border and the panel, and presents them.
    void present();

private:
    SDL_Window* window_ = nullptr;
    SDL_Renderer* renderer_ = nullptr;
    SDL_Texture* texture_ = nullptr;
    bool videoStarted_ = false;
    int textureWidth_ = 0, textureHeight_ = 0;
    bool errorBorder_ = false;
    Panel panel_;
    PanelPainter painter_;
    std::string error_;
    StartupTimes startup_;
};

}  // namespace viewer::window
