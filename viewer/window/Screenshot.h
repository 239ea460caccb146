// Screenshots of the window: the latest level scaled to the window's pixels the way the
// window shows it (nearest neighbour), written as PNG through primitives/base/AtomicFile.
#pragma once

#include <string>

#include "viewer/render/PngWriter.h"

namespace viewer::window {

// image stretched to width x height by nearest neighbour (blocks stay blocks).
render::Rgb8Image upscaleNearest(const render::Rgb8Image& image, int width, int height);

// The first "csgray-view-STEM-NNN.png" in the current directory that does not exist yet.
std::string nextScreenshotName(const std::string& partFile);

}  // namespace viewer::window
