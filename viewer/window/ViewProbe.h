// Click-to-probe in the window: the ray through a pixel, as the same JSON as `csgray probe`
// (viewer/cli/ProbeJson), a one-line summary for the title bar and the lines the panel shows.
#pragma once

#include <string>
#include <vector>

#include "io/Model.h"
#include "viewer/cli/LoadPart.h"

namespace viewer::window {

struct PixelProbe {
    std::string json;     // one ProbeJson object, no newline
    std::string summary;  // "3 spans; first hit cube at part.scad:4:5", or "no hit"
    // For the panel, like nirt: a header, then per span its t interval and, for each end, the
    // primitive, its module path, file:line:col and that source line's text.
    std::vector<std::string> lines;
};

// The primary ray through the centre of pixel (x, y) of a width x height view, probed.
PixelProbe probePixel(const LoadedPart& part, const render::Camera& camera, int width, int height,
                      int x, int y);

}  // namespace viewer::window
