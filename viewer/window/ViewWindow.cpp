#include "viewer/window/ViewWindow.h"

#include <SDL.h>

namespace viewer::window {

ViewWindow::ViewWindow(const std::string& title, int width, int height) {
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        error_ = std::string("cannot open a window: ") + SDL_GetError();
        return;
    }
    // Blocks, not blur: a coarse level should look like what it is.
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "0");
    window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                               width, height, SDL_WINDOW_RESIZABLE);
    if (!window_) {
        error_ = std::string("cannot open a window: ") + SDL_GetError();
        return;
    }
    renderer_ = SDL_CreateRenderer(window_, -1, 0);
    if (!renderer_) renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
    if (!renderer_) error_ = std::string("cannot draw in the window: ") + SDL_GetError();
}

ViewWindow::~ViewWindow() {
    if (texture_) SDL_DestroyTexture(texture_);
    if (renderer_) SDL_DestroyRenderer(renderer_);
    if (window_) SDL_DestroyWindow(window_);
    SDL_Quit();
}

void ViewWindow::setImage(const io::Rgb8Image& image) {
    if (!texture_ || textureWidth_ != image.width || textureHeight_ != image.height) {
        if (texture_) SDL_DestroyTexture(texture_);
        texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING,
                                     image.width, image.height);
        textureWidth_ = image.width;
        textureHeight_ = image.height;
    }
    if (texture_) SDL_UpdateTexture(texture_, nullptr, image.pixels.data(), image.width * 3);
}

void ViewWindow::setTitle(const std::string& title) {
    SDL_SetWindowTitle(window_, title.c_str());
}

void ViewWindow::present() {
    SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
    SDL_RenderClear(renderer_);
    if (texture_) SDL_RenderCopy(renderer_, texture_, nullptr, nullptr);
    if (errorBorder_) {
        int w = 0, h = 0;
        SDL_GetRendererOutputSize(renderer_, &w, &h);
        const int b = 6;  // pixels: visible, yet hides little of the part
        const SDL_Rect sides[] = {{0, 0, w, b}, {0, h - b, w, b}, {0, 0, b, h}, {w - b, 0, b, h}};
        SDL_SetRenderDrawColor(renderer_, 220, 30, 30, 255);
        SDL_RenderFillRects(renderer_, sides, 4);
    }
    SDL_RenderPresent(renderer_);
}

}  // namespace viewer::window
