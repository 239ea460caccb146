// A binary STL's triangles and signed volume (divergence theorem), read here (not by csgray's mesh
// readers, which some tests check): the oracle of tests that compare with OpenSCAD's STL.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "TextFiles.h"
#include "primitives/base/Math.h"

namespace csg::testing {

// The triangles of a binary STL (80-byte header, uint32 count, 50 bytes a triangle: normal,
// three float vertices, attribute), as OpenSCAD 2021 writes with --export-format binstl; none
// when the file is not well formed.
inline std::vector<std::array<Vec3, 3>> binaryStlTriangles(const std::filesystem::path& file) {
    const std::string bytes = readFile(file);
    std::vector<std::array<Vec3, 3>> triangles;
    if (bytes.size() < 84) return triangles;
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() != 84 + size_t(count) * 50) return triangles;
    for (uint32_t i = 0; i < count; ++i) {
        float f[9];
        std::memcpy(f, bytes.data() + 84 + size_t(i) * 50 + 12, sizeof f);
        triangles.push_back(
            {Vec3(f[0], f[1], f[2]), Vec3(f[3], f[4], f[5]), Vec3(f[6], f[7], f[8])});
    }
    return triangles;
}

// 0 when the file is not a well-formed binary STL.
inline double binaryStlVolume(const std::filesystem::path& file) {
    double volume = 0.0;
    for (const auto& [a, b, c] : binaryStlTriangles(file))
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    return volume;
}

}  // namespace csg::testing
