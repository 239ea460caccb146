#include "csg/SpanList.h"

namespace csg {
namespace {

bool apply(SetOp op, bool inA, bool inB) {
    switch (op) {
        case SetOp::Union:
            return inA || inB;
        case SetOp::Intersection:
            return inA && inB;
        case SetOp::Difference:
            return inA && !inB;
    }
    return false;
}

// A cursor over one operand's span ends, in order: in, out, in, out, ...
struct Cursor {
    const Span* spans;
    size_t count;
    size_t index = 0;
    bool inside = false;

    bool done() const { return index == count; }
    const Hit& hit() const { return inside ? spans[index].out : spans[index].in; }
    void advance() {
        if (inside) ++index;
        inside = !inside;
    }
};

}  // namespace

size_t mergeSpans(SetOp op, const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                  double originScale) {
    Cursor ca{a, na}, cb{b, nb};
    SpanWriter writer(out, originScale);
    const bool flipB = op == SetOp::Difference;
    bool inResult = false;
    Hit start;
    for (;;) {
        // Stop as soon as the rest of the result is decided.
        if (ca.done() && (cb.done() || op != SetOp::Union)) break;
        if (cb.done() && op == SetOp::Intersection) break;

        // Take the next event; both operands when their ends are exactly equal.
        const bool takeA = !ca.done() && (cb.done() || ca.hit().t <= cb.hit().t);
        const bool takeB = !cb.done() && (ca.done() || cb.hit().t <= ca.hit().t);
        Hit hitA, hitB;
        if (takeA) {
            hitA = ca.hit();
            ca.advance();
        }
        if (takeB) {
            hitB = cb.hit();
            hitB.flipped ^= flipB;
            cb.advance();
        }

        // Emit a boundary where the result changes, by the documented tie-break.
        const bool now = apply(op, ca.inside, cb.inside);
        if (now == inResult) continue;
        const Hit& boundary =
            !takeB || (takeA && (hitA.isSurface() || !hitB.isSurface())) ? hitA : hitB;
        if (now)
            start = boundary;
        else
            writer.emit({start, boundary});
        inResult = now;
    }
    // A union with one operand exhausted copies the other's tail through the loop above,
    // so inResult is false here whenever the inputs were closed lists.
    return writer.count();
}

}  // namespace csg
