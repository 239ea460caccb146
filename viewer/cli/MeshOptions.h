// Option values shared by export and compare.
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include "viewer/cli/Cli.h"

namespace viewer {

// A finite number > 0; what names the option in the error message.
inline double parsePositiveNumber(std::string_view text, std::string_view what) {
    double v = 0.0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || v <= 0.0)
        throw UsageError(std::string(what) + " expects a number > 0, got '" + std::string(text) +
                         "'");
    return v;
}

}  // namespace viewer
