#include "viewer/window/PanelDrawing.h"

#include <algorithm>

// stb_easy_font is all static functions; this file uses some of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include "viewer/window/SdlLibrary.h"

namespace viewer::window {

namespace {

constexpr float kLineHeight = 12.0f;  // stb_easy_font's own line advance, font pixels
constexpr float kPad = 3.0f;          // around the text on its band, font pixels
// The probe box keeps most of the part in sight: at most this share of the window's width and
// of the height left between the error and the status (the whole probe is on stderr).
constexpr float kProbeWidthShare = 0.6f, kProbeHeightShare = 0.5f;

}  // namespace

std::string printable(const std::string& text) {
    std::string out = text;
    for (char& c : out)
        if (c == '\t')
            c = ' ';
        else if (c < ' ' || c > '~')
            c = '?';
    return out;
}

float textWidth(const std::string& text) {
    std::string copy = printable(text);
    return float(stb_easy_font_width(copy.data()));
}

std::vector<std::string> wrapText(const std::string& text, float width) {
    std::vector<std::string> lines;
    std::string line;
    size_t i = 0;
    while (i < text.size()) {
        // The next word and the spaces before it.
        size_t end = text.find(' ', text.find_first_not_of(' ', i));
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(i, end - i);
        if (textWidth(line + word) <= width) {
            line += word;
            i = end;
            continue;
        }
        if (!line.empty()) {
            lines.push_back(line);
            line.clear();
            i = text.find_first_not_of(' ', i);  // a new line does not start with spaces
            if (i == std::string::npos) break;
            continue;
        }
        // One word wider than a line: as many characters as fit (at least one).
        size_t n = 1;
        while (i + n < end && textWidth(text.substr(i, n + 1)) <= width) ++n;
        lines.push_back(text.substr(i, n));
        i += n;
    }
    if (!line.empty()) lines.push_back(line);
    return lines;
}

std::string fitText(const std::string& text, float width) {
    if (textWidth(text) <= width) return text;
    std::string cut = text;
    while (!cut.empty() && textWidth(cut + "...") > width) cut.pop_back();
    return cut + "...";
}

float PanelPainter::band(SDL_Renderer* renderer, float x, float y, float width,
                         const std::vector<std::string>& lines, Colour text, Colour back) {
    const float height = float(lines.size()) * kLineHeight + kPad;
    const SDL_FRect backRect{x * scale_, y * scale_, width * scale_, height * scale_};
    sdl().SDL_SetRenderDrawColor(renderer, back.r, back.g, back.b, back.a);
    sdl().SDL_RenderFillRectF(renderer, &backRect);

    // Each stb quad is an axis-aligned bar: corners 0 and 2 are opposite.
    struct Vertex {
        float x, y, z;
        unsigned char rgba[4];
    };
    bars_.clear();
    float lineY = y + kPad;
    for (const std::string& line : lines) {
        std::string copy = printable(line);
        vertices_.resize(std::max<size_t>(vertices_.size(), copy.size() * 400 + 64));
        const int quads = stb_easy_font_print(x + kPad, lineY, copy.data(), nullptr,
                                              vertices_.data(), int(vertices_.size()));
        const auto* v = reinterpret_cast<const Vertex*>(vertices_.data());
        for (int q = 0; q < quads; ++q) {
            const Vertex& a = v[4 * q];
            const Vertex& c = v[4 * q + 2];
            bars_.push_back(
                SDL_FRect{a.x * scale_, a.y * scale_, (c.x - a.x) * scale_, (c.y - a.y) * scale_});
        }
        lineY += kLineHeight;
    }
    sdl().SDL_SetRenderDrawColor(renderer, text.r, text.g, text.b, text.a);
    if (!bars_.empty()) sdl().SDL_RenderFillRectsF(renderer, bars_.data(), int(bars_.size()));
    return height;
}

void PanelPainter::draw(SDL_Renderer* renderer, const Panel& panel) {
    if (!panel.visible) return;
    int outW = 0, outH = 0;
    sdl().SDL_GetRendererOutputSize(renderer, &outW, &outH);
    // Bigger text where there is room for it.
    scale_ = outH >= 480 ? 2.0f : 1.0f;
    const float width = float(outW) / scale_, height = float(outH) / scale_;
    const float textRoom = std::max(width - 2.0f * kPad, 8.0f);

    SDL_BlendMode previous;
    sdl().SDL_GetRenderDrawBlendMode(renderer, &previous);
    sdl().SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_BLEND);

    float top = 0.0f;
    if (!panel.error.empty()) {
        std::vector<std::string> lines = wrapText(panel.error, textRoom);
        if (lines.size() > 4) lines.resize(4);  // the whole message is on stderr
        top += band(renderer, 0.0f, top, width, lines, {255, 255, 255, 255}, {170, 20, 20, 215});
    }
    float bottom = height;
    if (!panel.status.empty()) {
        const std::vector<std::string> lines{fitText(panel.status, textRoom)};
        bottom -= float(lines.size()) * kLineHeight + kPad;
        band(renderer, 0.0f, bottom, width, lines, {230, 230, 230, 255}, {0, 0, 0, 160});
    }
    if (!panel.probe.empty()) {
        const size_t rows = std::max<size_t>(
            1, size_t(kProbeHeightShare * std::max(0.0f, bottom - top - kPad) / kLineHeight));
        const float room = std::max(textRoom * kProbeWidthShare, std::min(textRoom, 200.0f));
        std::vector<std::string> lines;
        float widest = 0.0f;
        for (const std::string& line : panel.probe) {
            if (lines.size() == rows) {
                lines.back() = "...";
                break;
            }
            lines.push_back(fitText(line, room));
            widest = std::max(widest, textWidth(lines.back()));
        }
        if (!lines.empty())
            band(renderer, 0.0f, top, widest + 2.0f * kPad, lines, {255, 235, 150, 255},
                 {0, 0, 0, 170});
    }
    sdl().SDL_SetRenderDrawBlendMode(renderer, previous);
}

}  // namespace viewer::window
