// What a primitive answers for a line o + t d: its spans along the whole line, before any
// clipping (t is the same in the world and local frames; a span end's face is primitive-defined).
#pragma once

#include <array>
#include <cassert>
#include <cstdint>
#include <limits>

namespace csg {

// The face of a span end that is the ray's own tmin/tmax (or an unbounded primitive's
// infinite end), not a surface.
inline constexpr uint16_t kClipFace = std::numeric_limits<uint16_t>::max();

// One primitive's spans along the whole line t in (-inf, inf), ascending and disjoint,
// before any clipping. Ends are finite except for unbounded primitives (half-spaces), whose
// infinite ends carry kClipFace. The leaf index is filled in by the caller.
struct LocalSpans {
    // A convex primitive gives 1 span, a torus 2, a degree-16 algebraic surface cut by its
    // box 9 (16 roots split the chord into 17 pieces, alternating, inside at both ends); a
    // patch set one per crossing of a sheet or per pair of a solid's: the teapot's worst line
    // crosses ~12 patches, 32 leaves room (further crossings of a line are dropped). A polygon
    // mesh closes a line's narrowest gaps until its spans fit (primitives/Polyhedron.h). Not
    // raised: one lives on the stack of every level of the recursive CSG walk.
    static constexpr int kCapacity = 32;
    struct Entry {
        double tIn, tOut;
        uint16_t faceIn, faceOut;
    };
    std::array<Entry, kCapacity> entries;
    int count = 0;
    // Set by a sheet (PatchSet with solid=false): every entry is a crossing, tIn == tOut.
    bool sheet = false;

    // What the caller keeps of the list, set before spans() so that a primitive may skip work
    // (it may also ignore it). The caller clips the spans at `from`: a span that ends before it
    // may be left out, and an end that lies before from - margin may be given as any value
    // before that. With firstOnly it reads only the first span left, and of that span only its
    // start and that it is there: the spans after one whose part past `from` is longer than
    // `margin` may be left out (margin covers the caller's sliver rule, so that span is the
    // first it keeps), and that span's end may be given as any value at or before the true one
    // that keeps its part past `from` so long, unless the span begins no later than
    // from + margin or an earlier span ends past `from` (a ray that starts inside a span, which
    // closest() answers with where the spans it fuses with that one end).
    double from = -std::numeric_limits<double>::infinity();
    double margin = 0.0;
    bool firstOnly = false;
    // The caller clips the spans at `to` too: an end that lies past to + margin may be given as
    // any value past that. A primitive that leaves out what lies past it sets cutAtTo, so that
    // the caller does not serve a farther `to` from the same list.
    double to = std::numeric_limits<double>::infinity();
    bool cutAtTo = false;

    void add(double tIn, uint16_t faceIn, double tOut, uint16_t faceOut) {
        assert(count < kCapacity && "a primitive produced more spans than LocalSpans holds");
        entries[count++] = {tIn, tOut, faceIn, faceOut};
    }
};

}  // namespace csg
