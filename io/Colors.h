// Color names and hex codes as OpenSCAD's color() reads them.
#pragma once

#include <optional>
#include <string_view>

#include "primitives/base/Math.h"

namespace io {

// RGBA in [0, 1] for a CSS color name (case-insensitive), "transparent", or "#rgb", "#rgba",
// "#rrggbb", "#rrggbbaa"; nothing when the text is neither.
std::optional<csg::Vec4> parseColor(std::string_view text);

}  // namespace io
