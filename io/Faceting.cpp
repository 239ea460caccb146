// OpenSCAD 2021.01's fragment rule and vertex placement (src/calc.cc, src/primitives.cc,
// src/degree_trig.cc at tag openscad-2021.01), written so that each double comes out of the
// same operations in the same order as there: a faceted solid's vertices are OpenSCAD's.
#include "io/Faceting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "io/Degrees.h"

namespace io {

namespace {

// degree_trig.cc: pi / 180 as the literal 0.017453292519943295769 (src/degree_trig.h
// M_DEG2RAD), applied by one multiplication.
constexpr double kDegreesToRadians = 0.017453292519943295769;
// sqrt(3) / 2 as degree_trig.h's literal M_SQRT3_4, and sqrt(1/2) as <cmath>'s M_SQRT1_2.
constexpr double kSqrt3Over2 = 0.86602540378443859659;
constexpr double kSqrtHalf = 0.70710678118654752440;
// tan(60) and tan(30) as degree_trig.h's M_SQRT3 and M_SQRT1_3; 180 / pi as its M_RAD2DEG.
constexpr double kSqrt3 = 1.73205080756887719318;
constexpr double kSqrtThird = 0.57735026918962573106;
constexpr double kRadiansToDegrees = 57.2957795130823208767;
// Beyond 2^52 degrees an angle has no fractional degrees left; degree_trig.cc gives NaN there.
constexpr double kHugeDegrees = double(int64_t(1) << 26) * 360.0 * double(int64_t(1) << 26);

// The angle reduced to [0, 360) as degree_trig.cc does it (floor, not fmod); NaN when it is
// too large to mean anything or not finite (the caller's branches then yield NaN too).
double reduceDegrees(double x) {
    if (x < 360.0 && x >= 0.0) return x;
    if (x < kHugeDegrees && x > -kHugeDegrees) return x - 360.0 * std::floor(x / 360.0);
    return std::numeric_limits<double>::quiet_NaN();
}

void closeFace(FacetedSolid& solid) {
    solid.faceStarts.push_back(uint32_t(solid.faceVertices.size()));
}

}  // namespace

double openscadSinDegrees(double degrees) {
    double x = reduceDegrees(degrees);
    if (std::isnan(x)) return x;
    const bool oppose = x >= 180.0;
    if (oppose) x -= 180.0;
    if (x > 90.0) x = 180.0 - x;
    if (x < 45.0) {
        x = x == 30.0 ? 0.5 : std::sin(x * kDegreesToRadians);
    } else if (x == 45.0) {
        x = kSqrtHalf;
    } else if (x == 60.0) {
        x = kSqrt3Over2;
    } else {
        x = std::cos((90.0 - x) * kDegreesToRadians);
    }
    return oppose ? -x : x;
}

double openscadCosDegrees(double degrees) {
    double x = reduceDegrees(degrees);
    if (std::isnan(x)) return x;
    bool oppose = x >= 180.0;
    if (oppose) x -= 180.0;
    if (x > 90.0) {
        x = 180.0 - x;
        oppose = !oppose;
    }
    if (x > 45.0) {
        x = x == 60.0 ? 0.5 : std::sin((90.0 - x) * kDegreesToRadians);
    } else if (x == 45.0) {
        x = kSqrtHalf;
    } else if (x == 30.0) {
        x = kSqrt3Over2;
    } else {
        x = std::cos(x * kDegreesToRadians);
    }
    return oppose ? -x : x;
}

double openscadTanDegrees(double degrees) {
    // Reduced to [0, 180) by whole half turns; their parity signs the exact 0 and infinity.
    const double cycles = std::floor(degrees / 180.0);
    double x = degrees;
    if (!(x < 180.0 && x >= 0.0)) {
        if (!(x < kHugeDegrees && x > -kHugeDegrees))
            return std::numeric_limits<double>::quiet_NaN();
        x -= 180.0 * cycles;
    }
    const bool even = std::fmod(cycles, 2.0) == 0.0;
    const bool oppose = x > 90.0;
    if (oppose) x = 180.0 - x;
    if (x == 0.0) {
        x = even ? 0.0 : -0.0;
    } else if (x == 30.0) {
        x = kSqrtThird;
    } else if (x == 45.0) {
        x = 1.0;
    } else if (x == 60.0) {
        x = kSqrt3;
    } else if (x == 90.0) {
        x = even ? std::numeric_limits<double>::infinity()
                 : -std::numeric_limits<double>::infinity();
    } else {
        x = std::tan(x * kDegreesToRadians);
    }
    return oppose ? -x : x;
}

// The inverse functions round to a whole degree when the forward function of that degree gives
// the argument back exactly (atan2: when within 3e-14 of it), so that acos(-0.5) is 120.
double openscadAsinDegrees(double x) {
    const double degrees = std::asin(x) * kRadiansToDegrees;
    const double whole = std::round(degrees);
    return openscadSinDegrees(whole) == x ? whole : degrees;
}

double openscadAcosDegrees(double x) {
    const double degrees = std::acos(x) * kRadiansToDegrees;
    const double whole = std::round(degrees);
    return openscadCosDegrees(whole) == x ? whole : degrees;
}

double openscadAtanDegrees(double x) {
    const double degrees = std::atan(x) * kRadiansToDegrees;
    const double whole = std::round(degrees);
    return openscadTanDegrees(whole) == x ? whole : degrees;
}

double openscadAtan2Degrees(double y, double x) {
    const double degrees = std::atan2(y, x) * kRadiansToDegrees;
    const double whole = std::round(degrees);
    return std::fabs(degrees - whole) < 3.0e-14 ? whole : degrees;
}

const char* curveModeName(CurveMode mode) {
    switch (mode) {
        case CurveMode::Auto:
            return "auto";
        case CurveMode::Exact:
            return "exact";
        case CurveMode::OpenScad:
            return "openscad";
    }
    return "auto";
}

std::optional<CurveMode> parseCurveMode(std::string_view name) {
    for (CurveMode mode : {CurveMode::Auto, CurveMode::Exact, CurveMode::OpenScad})
        if (name == curveModeName(mode)) return mode;
    return std::nullopt;
}

int64_t fragments(double r, double fn, double fa, double fs) {
    constexpr double kMaxCount = double(std::numeric_limits<int32_t>::max());
    if (r < kGridFine || std::isinf(fn) || std::isnan(fn)) return 3;
    if (fn > 0.0) return int64_t(std::min(fn >= 3 ? fn : 3.0, kMaxCount));
    const double count = std::ceil(std::fmax(std::fmin(360.0 / fa, r * 2 * M_PI / fs), 5));
    return int64_t(std::min(count, kMaxCount));
}

namespace {

// OpenSCAD's static_cast<int>(ceil(x)) for the counts it can reach, saturating instead of
// overflowing (a count past INT32_MAX, or $fa = 0, is refused later by its size).
int64_t ceilCount(double x) {
    constexpr double kMaxCount = double(std::numeric_limits<int32_t>::max());
    if (std::isnan(x)) return 1;
    return int64_t(std::clamp(std::ceil(x), -kMaxCount, kMaxCount));
}

// calc.cc's helix_arc_length: a vertex at radius sqrt(rSquared) climbing `height` while it
// turns through `twist` degrees (> 0).
double helixLength(double rSquared, double height, double twist) {
    const double turn = twist * kDegreesToRadians;
    const double c = height / turn;
    return turn * std::sqrt(rSquared + c * c);
}

// calc.cc's archimedes_length: the arc of the spiral r = a theta from 0 to theta.
double archimedesLength(double a, double theta) {
    return 0.5 * a * (theta * std::sqrt(1 + theta * theta) + std::asinh(theta));
}

int64_t helixSlices(double rSquared, double height, double twist, const FragmentSettings& s) {
    twist = std::fabs(twist);
    // At least 3 slices a turn: 180 degrees in one slice is never a manifold.
    const int64_t least = std::max<int64_t>(ceilCount(twist / 120.0), 1);
    if (std::sqrt(rSquared) < kGridFine || std::isinf(s.fn) || std::isnan(s.fn)) return least;
    if (s.fn > 0.0) return std::max(ceilCount(twist / 360.0 * s.fn), least);
    const int64_t byAngle = ceilCount(twist / s.fa);
    const int64_t byLength = ceilCount(helixLength(rSquared, height, twist) / s.fs);
    return std::max(std::min(byAngle, byLength), least);
}

// A uniform scale k != 1 with the twist: the vertex follows a conical helix, whose plan is a
// piece of an Archimedean spiral.
int64_t conicalHelixSlices(double rSquared, double height, double twist, double k,
                           const FragmentSettings& s) {
    twist = std::fabs(twist);
    const double r = std::sqrt(rSquared);
    const int64_t least = std::max<int64_t>(ceilCount(twist / 120.0), 1);
    if (r < kGridFine || std::isinf(s.fn) || std::isnan(s.fn)) return least;
    if (s.fn > 0.0) return std::max(ceilCount(twist * s.fn / 360), least);
    const double turn = twist * kDegreesToRadians;
    // The spiral's angle where the scale would reach 0, and where this piece starts.
    const double end = k > 1 ? turn * k / (k - 1) : turn / (1 - k);
    const double start = end - turn;
    const double a = r / end;
    const double spiral = archimedesLength(a, end) - archimedesLength(a, start);
    const double length = std::sqrt(spiral * spiral + height * height);
    const int64_t byLength = ceilCount(length / s.fs);
    const int64_t byAngle = ceilCount(twist / s.fa);
    return std::max(std::min(byAngle, byLength), least);
}

int64_t diagonalSlices(double deltaSquared, double height, const FragmentSettings& s) {
    if (std::sqrt(deltaSquared) < kGridFine || std::isinf(s.fn) || std::isnan(s.fn)) return 1;
    if (s.fn > 0.0) return std::max<int64_t>(ceilCount(std::trunc(s.fn)), 1);
    return std::max<int64_t>(ceilCount(std::sqrt(deltaSquared + height * height) / s.fs), 1);
}

}  // namespace

int64_t extrudeSlices(double rmaxSquared, double deltaSquared, double height, double twist,
                      csg::Vec2 scale, const FragmentSettings& settings) {
    if (twist != 0.0) {
        // OpenSCAD 2021 takes the plain helix for two unequal scales too.
        if ((scale.x == 1.0 && scale.y == 1.0) || scale.x != scale.y)
            return helixSlices(rmaxSquared, height, twist, settings);
        return conicalHelixSlices(rmaxSquared, height, twist, scale.x, settings);
    }
    if (scale.x != scale.y) return diagonalSlices(deltaSquared, height, settings);
    return 1;
}

bool fnDecidesCount(const FragmentSettings& settings) {
    return !std::isfinite(settings.fn) || settings.fn > 0.0;
}

bool isFaceted(CurveMode mode, const FragmentSettings& settings) {
    switch (mode) {
        case CurveMode::Exact:
            return false;
        case CurveMode::OpenScad:
            return true;
        case CurveMode::Auto:
            return fnDecidesCount(settings);
    }
    return false;
}

std::vector<csg::Vec2> circleVertices(double r, int64_t n) {
    std::vector<csg::Vec2> circle(static_cast<size_t>(n));
    for (int64_t i = 0; i < n; ++i) {
        // OpenSCAD's int i and int fragments, converted to double for the division.
        const double phi = (360.0 * double(i)) / double(n);
        circle[size_t(i)] = {r * openscadCosDegrees(phi), r * openscadSinDegrees(phi)};
    }
    return circle;
}

uint64_t facetedCylinderFaceCount(int64_t n, double r1, double r2) {
    return uint64_t(n) + (r1 > 0.0 ? 1 : 0) + (r2 > 0.0 ? 1 : 0);
}

uint64_t facetedSphereFaceCount(int64_t n) {
    return uint64_t(n) * uint64_t(sphereRingCount(n) - 1) + 2;
}

FacetedSolid facetedCylinder(double r1, double r2, double z1, double z2, int64_t n) {
    FacetedSolid solid;
    const auto count = uint32_t(n);
    // One end's vertices: its ring, or the apex when its radius is 0 (OpenSCAD makes n copies
    // of the apex; one vertex is the same solid). Returns the index of the end's first vertex.
    auto addEnd = [&](double r, double z) {
        const auto first = uint32_t(solid.vertices.size());
        if (r > 0.0) {
            for (const csg::Vec2& p : circleVertices(r, n)) solid.vertices.push_back({p.x, p.y, z});
        } else {
            solid.vertices.push_back({0.0, 0.0, z});
        }
        return first;
    };
    const uint32_t bottom = addEnd(r1, z1), top = addEnd(r2, z2);
    solid.faceVertices.reserve(size_t(4 * count + 2 * count));
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t j = (i + 1) % count;
        // Counter-clockwise from outside: along the bottom ring, then back along the top.
        if (r1 > 0.0)
            solid.faceVertices.insert(solid.faceVertices.end(), {bottom + i, bottom + j});
        else
            solid.faceVertices.push_back(bottom);
        if (r2 > 0.0)
            solid.faceVertices.insert(solid.faceVertices.end(), {top + j, top + i});
        else
            solid.faceVertices.push_back(top);
        closeFace(solid);
    }
    if (r1 > 0.0) {  // seen from below: clockwise in x, y
        for (uint32_t i = count; i-- > 0;) solid.faceVertices.push_back(bottom + i);
        closeFace(solid);
    }
    if (r2 > 0.0) {
        for (uint32_t i = 0; i < count; ++i) solid.faceVertices.push_back(top + i);
        closeFace(solid);
    }
    return solid;
}

FacetedSolid facetedSphere(double r, int64_t n) {
    FacetedSolid solid;
    const auto count = uint32_t(n);
    const auto rings = uint32_t(sphereRingCount(n));
    solid.vertices.reserve(size_t(rings) * count);
    for (uint32_t i = 0; i < rings; ++i) {
        // OpenSCAD: phi = (180.0 * (i + 0.5)) / rings, with int i and int rings.
        const double phi = (180.0 * (double(i) + 0.5)) / double(rings);
        const double ringRadius = r * openscadSinDegrees(phi);
        const double z = r * openscadCosDegrees(phi);
        for (const csg::Vec2& p : circleVertices(ringRadius, n))
            solid.vertices.push_back({p.x, p.y, z});
    }
    auto vertex = [count](uint32_t ring, uint32_t k) { return ring * count + k % count; };
    solid.faceVertices.reserve(size_t(4) * count * rings);
    for (uint32_t i = 0; i + 1 < rings; ++i) {
        for (uint32_t k = 0; k < count; ++k) {
            // Counter-clockwise from outside: down the meridian at k, back up the one at k + 1.
            solid.faceVertices.insert(
                solid.faceVertices.end(),
                {vertex(i, k), vertex(i + 1, k), vertex(i + 1, k + 1), vertex(i, k + 1)});
            closeFace(solid);
        }
    }
    for (uint32_t k = 0; k < count; ++k) solid.faceVertices.push_back(vertex(0, k));
    closeFace(solid);
    for (uint32_t k = count; k-- > 0;) solid.faceVertices.push_back(vertex(rings - 1, k));
    closeFace(solid);
    return solid;
}

}  // namespace io
