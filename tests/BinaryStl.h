// A binary STL's signed volume by the divergence theorem, read here (not by csgray's mesh
// readers, which some tests check): the oracle of tests that compare with OpenSCAD's STL.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "TextFiles.h"
#include "primitives/base/Math.h"

namespace csg::testing {

// 0 when the file is not a well-formed binary STL.
inline double binaryStlVolume(const std::filesystem::path& file) {
    const std::string bytes = readFile(file);
    if (bytes.size() < 84) return 0.0;
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() != 84 + size_t(count) * 50) return 0.0;
    double volume = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        float f[9];
        std::memcpy(f, bytes.data() + 84 + size_t(i) * 50 + 12, sizeof f);
        const Vec3 a(f[0], f[1], f[2]), b(f[3], f[4], f[5]), c(f[6], f[7], f[8]);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return volume;
}

}  // namespace csg::testing
