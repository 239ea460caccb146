// Regularized set operations on span lists, and the one rule that regularizes them.
//
// The coincidence rule (the only tolerance in CSG merging, see tol::kCoincidentRel):
// ends a and b coincide when |a - b| <= kCoincidentRel * (originScale + max(|a|, |b|)).
// Every list a merge writes is regularized by it: a span whose length is within the
// tolerance is dropped (tangent touches, slivers between coincident faces) and a gap within
// the tolerance is closed (face-sharing parts become one span).
//
// The tie-break (the only one): events of both operands at exactly the same t are applied
// together, and the boundary the result gets there is the left operand's hit, unless the
// left hit is a clip end (kClipFace) and the right one a surface; a union's two surfaces, or
// two clip ends, give the one of the lower leaf (the union's result is then the same in any
// merge order).
// Hence A u A = A, A n A = A, A - A = {} with A's own hits, and clip ends introduced by
// narrowing never leak out.
//
// Sheets (Hit::sheet, the crossings of an open surface) are zero-length spans that no rule
// above drops: a union keeps each one that no solid span covers; difference and intersection
// never see one (compile rejects a sheet under them).
#pragma once

#include <cmath>
#include <cstddef>

#include "csg/Span.h"
#include "primitives/base/Tolerances.h"

namespace csg {

enum class SetOp : uint8_t { Union, Intersection, Difference };

// Half-width of the coincidence window around ends a and b (unit: t). Infinite ends (an
// unbounded half-space) do not widen it: a span reaching infinity is never a sliver.
inline double coincidenceSlack(double originScale, double a, double b) {
    const double ta = std::isfinite(a) ? std::abs(a) : 0.0;
    const double tb = std::isfinite(b) ? std::abs(b) : 0.0;
    return tol::kCoincidentRel * (originScale + std::max(ta, tb));
}

// to = from, one field at a time (see SpanWriter::emit for why).
inline void storeHit(Hit& to, const Hit& from) {
    to.t = from.t;
    to.leaf = from.leaf;
    to.face = from.face;
    to.flipped = from.flipped;
    to.sheet = from.sheet;
}

// Appends spans in ascending order and keeps the result regularized: drops spans no longer
// than the coincidence slack and fuses a span into its predecessor across a gap no wider.
// originScale is |o| / |d| of the ray (see tol::kCoincidentRel).
class SpanWriter {
public:
    SpanWriter(Span* out, double originScale) : out_(out), originScale_(originScale) {}

    void emit(const Span& s) {
        if (s.out.t - s.in.t <= coincidenceSlack(originScale_, s.in.t, s.out.t)) return;
        if (count_ > 0) {
            Span& last = out_[count_ - 1];
            if (s.in.t - last.out.t <= coincidenceSlack(originScale_, last.out.t, s.in.t)) {
                storeHit(last.out, s.out);
                return;
            }
        }
        // Field by field: a span just built is in registers, and a whole-struct copy of it
        // compiles to a spill and 16-byte reloads across narrower stores, which stalls
        // store-to-load forwarding, a large share of evalLeaf's time on csg_grid
        // (bench/README.md, span stores field by field).
        Span& to = out_[count_++];
        storeHit(to.in, s.in);
        storeHit(to.out, s.out);
    }
    size_t count() const { return count_; }

private:
    Span* out_;
    double originScale_;
    size_t count_ = 0;
};

// One linear merge: writes op(a, b) to out and returns its length. a and b are sorted,
// disjoint lists; out has room for na + nb spans and overlaps neither input. For a
// difference, the hits taken from b are flipped (the cut's surface faces the other way).
size_t mergeSpans(SetOp op, const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                  double originScale);

// mergeSpans for lists known to hold no sheet crossings (a scene compiled without sheets):
// the same result, without scanning the operands for sheets on every merge.
size_t mergeSolidSpans(SetOp op, const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                       double originScale);

}  // namespace csg
