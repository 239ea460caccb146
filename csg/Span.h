// Notation used throughout csg/ and primitives/:
//   t       ray parameter; the point is o + t d, the same t in world and local frames.
//   span    a closed interval [in.t, out.t] of t where the ray is inside a solid.
//   face    which surface of a leaf's primitive bounds a span end (primitive-defined);
//           kClipFace marks an end that is the ray's own tmin/tmax, not a surface.
//   flipped the solid lies on the other side of that surface (a difference's right
//           operand): the outward normal is the primitive's normal negated.
#pragma once

#include <array>
#include <cassert>
#include <cstdint>
#include <limits>

namespace csg {

inline constexpr uint16_t kClipFace = std::numeric_limits<uint16_t>::max();

// Which surface bounds a span end. Points and normals are not stored: they are computed
// on request from (leaf, face) by the scene, so shadow rays never pay for them.
struct Hit {
    double t = 0.0;
    uint32_t leaf = 0;
    uint16_t face = kClipFace;
    bool flipped = false;
    // The end of a zero-length span that is a crossing of a sheet: an open surface with no
    // inside (a bezier_patch with solid=false). Its span has in == out; merges keep it where
    // no solid covers it instead of dropping it as a sliver.
    bool sheet = false;

    bool isSurface() const { return face != kClipFace; }
};

struct Span {
    Hit in;
    Hit out;
};

// One primitive's spans along the whole line t in (-inf, inf), ascending and disjoint,
// before any clipping. Ends are finite except for unbounded primitives (half-spaces), whose
// infinite ends carry kClipFace. The leaf index is filled in by the caller.
struct LocalSpans {
    // A convex primitive gives 1 span, a torus 2, a degree-16 algebraic surface cut by its
    // box 9 (16 roots split the chord into 17 pieces, alternating, inside at both ends); a
    // patch set one per crossing of a sheet or per pair of a solid's: the teapot's worst line
    // crosses ~12 patches, 32 leaves room (further crossings of a line are dropped).
    static constexpr int kCapacity = 32;
    struct Entry {
        double tIn, tOut;
        uint16_t faceIn, faceOut;
    };
    std::array<Entry, kCapacity> entries;
    int count = 0;
    // Set by a sheet (PatchSet with solid=false): every entry is a crossing, tIn == tOut.
    bool sheet = false;

    void add(double tIn, uint16_t faceIn, double tOut, uint16_t faceOut) {
        assert(count < kCapacity && "a primitive produced more spans than LocalSpans holds");
        entries[count++] = {tIn, tOut, faceIn, faceOut};
    }
};

}  // namespace csg
