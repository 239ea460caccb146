// OpenEXR output of a render: 32-bit float linear RGB channels R, G, B with ZIP compression,
// the HDR format compositing tools read (PFM is the simpler one). Written through
// primitives/base/AtomicFile like the other formats: a failed or interrupted write leaves no file.
#pragma once

#include <filesystem>
#include <string>

#include "viewer/render/TileRenderer.h"

namespace viewer::render {

// Returns an empty string on success, else the reason (the target is then untouched).
std::string writeExr(const std::filesystem::path& path, const LinearImage& image);

}  // namespace viewer::render
