// Draws the Panel (Panel.h) over the picture with stb_easy_font (Debian libstb-dev): a bitmap
// font made of axis-aligned bars, so each glyph is a few SDL_RenderFillRects and no texture,
// font file or GUI library is needed. Text sits on translucent bands so it reads over any
// part. Layout, in font pixels scaled 2x on windows at least 480 pixels high:
//   top:    the error, wrapped, on a red band across the window
//   below:  the probe, one line per row, on a dark box as wide as its longest line
//   bottom: the status line on a dark band
#pragma once

#include <string>
#include <vector>

#include "viewer/window/Panel.h"

struct SDL_Renderer;
struct SDL_FRect;

namespace viewer::window {

class PanelPainter {
public:
    // Draws over what the renderer holds now, in its output pixels. Nothing when hidden.
    void draw(SDL_Renderer* renderer, const Panel& panel);

private:
    struct Colour {
        unsigned char r, g, b, a;
    };
    // Fills one band: a background rectangle and the lines on it, top-left at (x, y) in font
    // pixels. Returns the band's height in font pixels.
    float band(SDL_Renderer* renderer, float x, float y, float width,
               const std::vector<std::string>& lines, Colour text, Colour back);

    float scale_ = 1.0f;          // output pixels per font pixel
    std::vector<char> vertices_;  // stb_easy_font's quads, reused from frame to frame
    std::vector<SDL_FRect> bars_;
};

// Helpers of the layout, exposed for tests. Widths are in font pixels.
// The text with every byte stb_easy_font cannot draw (outside ' '..'~') replaced by '?'.
std::string printable(const std::string& text);
float textWidth(const std::string& text);
// Greedy word wrap to lines no wider than width (a word longer than a line is cut).
std::vector<std::string> wrapText(const std::string& text, float width);
// The text, cut and ended with "..." when wider than width.
std::string fitText(const std::string& text, float width);

}  // namespace viewer::window
