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

// OpenSCAD 2021.01's sin_degrees and cos_degrees (src/degree_trig.cc), bit for bit: exact at
// multiples of 30, 45, 60 and 90 degrees, otherwise sin or cos of the angle folded into
// [0, 45] and converted with one multiplication by the rounded pi/180. Faceting (io/Faceting.h)
// places OpenSCAD's vertices with these, so a faceted solid's vertices are OpenSCAD's doubles.
// The language's sin(), cos() and tan() use these (BOSL2 builds its geometry with them and
// its tests compare to OpenSCAD's doubles); rotate() still uses the pair above: moving it
// changes rotations by 45 and 60 degrees by an ulp, i.e. the outputs of parts that have them,
// which is a change of its own.
double openscadSinDegrees(double degrees);
double openscadCosDegrees(double degrees);
// The rest of degree_trig.cc: tan exact at 0, 30, 45, 60 and 90 degrees; asin, acos, atan and
// atan2 in degrees, snapped to a whole degree as OpenSCAD 2021 does (acos(-0.5) is 120,
// not 120.00000000000001; BOSL2's tests compare them exactly).
double openscadTanDegrees(double degrees);
double openscadAsinDegrees(double x);
double openscadAcosDegrees(double x);
double openscadAtanDegrees(double x);
double openscadAtan2Degrees(double y, double x);

}  // namespace io
