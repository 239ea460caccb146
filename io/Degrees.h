// Trigonometry in degrees, exact at multiples of 30 and 90 degrees as OpenSCAD's is, so that
// rotate([0, 0, 90]) is an exact permutation and cos(90) is 0, not 6e-17.
#pragma once

#include <cmath>
#include <numbers>

namespace io {

inline double sinDegrees(double degrees) {
    if (!std::isfinite(degrees)) return std::nan("");
    double x = std::fmod(degrees, 360.0);
    if (x < 0) x += 360.0;
    double sign = 1.0;
    if (x >= 180.0) {
        x -= 180.0;
        sign = -1.0;
    }
    if (x > 90.0) x = 180.0 - x;  // sin(180 - x) = sin(x)
    if (x == 0.0) return 0.0;
    if (x == 30.0) return sign * 0.5;
    if (x == 90.0) return sign;
    return sign * std::sin(x * std::numbers::pi / 180.0);
}

inline double cosDegrees(double degrees) {
    if (!std::isfinite(degrees)) return std::nan("");
    double x = std::fmod(degrees, 360.0);
    if (x < 0) x += 360.0;
    return sinDegrees(x + 90.0);
}

}  // namespace io
