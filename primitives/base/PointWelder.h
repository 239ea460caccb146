// Welding points of equal position as they come: the one weld of the mesh primitive
// (Polyhedron::make) and of the mesh files read back (weldExactDuplicates). -0 and +0 are one
// position (== says so); each distinct position keeps the value it first came with and its index in
// order of first appearance.
#pragma once

#include <cstdint>
#include <vector>

#include "primitives/base/Math.h"

namespace csg {

class PointWelder {
public:
    // expectedPoints sizes the table (a closed mesh has about one position per six corners);
    // it grows as needed.
    explicit PointWelder(size_t expectedPoints = 0);

    // The index of p's position among the distinct ones, added when new.
    uint32_t add(const Vec3& p);

    size_t size() const { return distinct_.size(); }
    // The distinct positions, in order of first appearance; the welder is empty after.
    std::vector<Vec3> take();

private:
    void grow(size_t capacity);
    // An open-addressing table of indices into distinct_, probed linearly from a hash of the
    // position's bits: sorting the corners by position took a fifth of a 2.3-million-triangle
    // STL's load (bench/README.md, "Loading a large mesh").
    std::vector<uint32_t> table_;
    uint64_t mask_ = 0;
    std::vector<Vec3> distinct_;
};

}  // namespace csg
