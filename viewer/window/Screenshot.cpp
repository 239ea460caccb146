#include "viewer/window/Screenshot.h"

#include <cstdio>
#include <filesystem>

namespace viewer::window {

render::Rgb8Image upscaleNearest(const render::Rgb8Image& image, int width, int height) {
    render::Rgb8Image out(width, height);
    if (image.width <= 0 || image.height <= 0) return out;
    for (int y = 0; y < height; ++y) {
        const int sy = int(int64_t(y) * image.height / height);
        for (int x = 0; x < width; ++x) {
            const int sx = int(int64_t(x) * image.width / width);
            const uint8_t* from = &image.pixels[(size_t(sy) * image.width + sx) * 3];
            uint8_t* to = out.row(y) + size_t(x) * 3;
            to[0] = from[0];
            to[1] = from[1];
            to[2] = from[2];
        }
    }
    return out;
}

std::string nextScreenshotName(const std::string& partFile) {
    const std::string stem = std::filesystem::path(partFile).stem().string();
    for (int n = 1;; ++n) {
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, "-%03d.png", n);
        const std::string name = "csgray-view-" + stem + suffix;
        std::error_code error;
        if (!std::filesystem::exists(name, error) || n >= 100000) return name;
    }
}

}  // namespace viewer::window
