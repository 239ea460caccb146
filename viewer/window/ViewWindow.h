// The SDL2 side of `csgray view`: one window, its renderer and one streaming texture that
// holds the latest refinement level. The texture has the level's size and is stretched to the
// window with nearest-neighbour sampling, which is what shows a coarse level as blocks.
// SDL has no text, so status and errors go to the title bar; an error also draws a red border.
#pragma once

#include <string>

#include "io/PngWriter.h"

struct SDL_Window;
struct SDL_Renderer;
struct SDL_Texture;

namespace viewer::window {

class ViewWindow {
public:
    // Calls SDL_Init(VIDEO). ok() is false (and error() says why) when no display is usable.
    ViewWindow(const std::string& title, int width, int height);
    ~ViewWindow();
    ViewWindow(const ViewWindow&) = delete;
    ViewWindow& operator=(const ViewWindow&) = delete;

    bool ok() const { return renderer_ != nullptr; }
    const std::string& error() const { return error_; }

    // Replaces the picture (any size; stretched to the window when drawn).
    void setImage(const io::Rgb8Image& image);
    void setTitle(const std::string& title);
    // A red frame around the picture: the part on screen is not what the file says.
    void setErrorBorder(bool on) { errorBorder_ = on; }
    // Draws the picture (and the border) and presents it.
    void present();

private:
    SDL_Window* window_ = nullptr;
    SDL_Renderer* renderer_ = nullptr;
    SDL_Texture* texture_ = nullptr;
    int textureWidth_ = 0, textureHeight_ = 0;
    bool errorBorder_ = false;
    std::string error_;
};

}  // namespace viewer::window
