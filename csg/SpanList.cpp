#include "csg/SpanList.h"

namespace csg {
namespace {

template <SetOp Op>
bool apply(bool inA, bool inB) {
    if constexpr (Op == SetOp::Union) return inA || inB;
    if constexpr (Op == SetOp::Intersection) return inA && inB;
    return inA && !inB;
}

// A cursor over one operand's solid span ends, in order: in, out, in, out, ... Sheet
// crossings (Hit::sheet) enclose nothing, so they are no events of the solid: skipped here
// when the operand may hold some (SkipSheets).
template <bool SkipSheets>
struct Cursor {
    const Span* spans;
    size_t count;
    size_t index = 0;
    bool inside = false;

    Cursor(const Span* s, size_t n) : spans(s), count(n) { skipSheets(); }
    bool done() const { return index == count; }
    const Hit& hit() const { return inside ? spans[index].out : spans[index].in; }
    void advance() {
        if (inside) ++index, skipSheets();
        inside = !inside;
    }
    void skipSheets() {
        if constexpr (SkipSheets)
            while (index < count && spans[index].in.sheet) ++index;
    }
};

// Two single spans are the commonest merge (a part's box and sphere, its bores): the three
// functions below give what mergeSolid gives them, hit for hit, without its event loop (the
// merge took 139 instructions on csg_grid, bench/README.md; spanlist_test holds them to the
// loop's answers).

// Of two ends at one t, the one mergeSolid takes: a surface over a clip end, else the left.
const Hit& tiedEnd(const Hit& a, const Hit& b) {
    return a.isSurface() || !b.isSurface() ? a : b;
}

// The intersection: the later entry (at one t, the tie-break's) and the earlier exit
// (likewise); nothing when the later entry is not before the earlier exit.
size_t intersectSingle(const Span& a, const Span& b, Span* out, double originScale) {
    const Hit* start;
    if (a.in.t < b.in.t) {
        if (!(b.in.t < a.out.t)) return 0;
        start = &b.in;
    } else if (b.in.t < a.in.t) {
        if (!(a.in.t < b.out.t)) return 0;
        start = &a.in;
    } else {
        start = &tiedEnd(a.in, b.in);
    }
    const Hit& end = a.out.t < b.out.t ? a.out : b.out.t < a.out.t ? b.out : tiedEnd(a.out, b.out);
    SpanWriter writer(out, originScale);
    writer.emit({*start, end});
    return writer.count();
}

// Of two ends of a union at one t, the one mergeSolid takes: the lower leaf's when both are
// surfaces or both clip ends.
const Hit& tiedUnionEnd(const Hit& a, const Hit& b) {
    return a.isSurface() == b.isSurface() && b.leaf < a.leaf ? b : tiedEnd(a, b);
}

// The union: both, in order, when a gap parts them (the writer fuses one within the slack);
// else the earlier entry and the later exit, at one t by the tie-break.
size_t uniteSingle(const Span& a, const Span& b, Span* out, double originScale) {
    SpanWriter writer(out, originScale);
    if (a.out.t < b.in.t || b.out.t < a.in.t) {
        const bool aFirst = a.out.t < b.in.t;
        writer.emit(aFirst ? a : b);
        writer.emit(aFirst ? b : a);
        return writer.count();
    }
    const Hit& start = a.in.t < b.in.t ? a.in : b.in.t < a.in.t ? b.in : tiedUnionEnd(a.in, b.in);
    const Hit& end = a.out.t > b.out.t   ? a.out
                     : b.out.t > a.out.t ? b.out
                                         : tiedUnionEnd(a.out, b.out);
    writer.emit({start, end});
    return writer.count();
}

// The difference: A where B leaves it, before B and past it, with B's hits flipped; where an
// end of B meets an end of A, the tie-break's.
size_t subtractSingle(const Span& a, const Span& b, Span* out, double originScale) {
    SpanWriter writer(out, originScale);
    Span cut = b;
    cut.in.flipped = !cut.in.flipped;
    cut.out.flipped = !cut.out.flipped;
    if (b.out.t < a.in.t || a.out.t < b.in.t) {
        writer.emit(a);
    } else if (b.out.t == a.in.t) {
        writer.emit({tiedEnd(a.in, cut.out), a.out});
    } else if (a.out.t == b.in.t) {
        writer.emit({a.in, tiedEnd(a.out, cut.in)});
    } else {
        if (a.in.t < b.in.t) writer.emit({a.in, cut.in});
        if (b.out.t < a.out.t) writer.emit({cut.out, a.out});
    }
    return writer.count();
}

// The linear merge, with the operation and the sheet skipping fixed at compile time (they
// are per-call constants, and the loop runs once per span end).
template <SetOp Op, bool SkipSheets>
size_t mergeSolid(const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                  double originScale) {
    Cursor<SkipSheets> ca(a, na), cb(b, nb);
    SpanWriter writer(out, originScale);
    constexpr bool flipB = Op == SetOp::Difference;
    bool inResult = false;
    Hit start;
    for (;;) {
        // Stop as soon as the rest of the result is decided.
        if (ca.done() && (cb.done() || Op != SetOp::Union)) break;
        if (cb.done() && Op == SetOp::Intersection) break;

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
        const bool now = apply<Op>(ca.inside, cb.inside);
        if (now == inResult) continue;
        // Of two ends at one t, a surface over a clip end; of two surfaces or two clip ends of
        // a union (coincident faces, or a ray that starts or stops inside both operands), the
        // lower leaf, so that a union's result does not depend on the order its children are
        // merged in (the structures of --accel visit them in different orders, and a BVH in
        // an order that changes with the ray: two lines through one pair of coincident faces
        // must name the same one, or the exact boundary keeps both or neither).
        const Hit& boundary = !takeB               ? hitA
                              : !takeA             ? hitB
                              : Op == SetOp::Union ? tiedUnionEnd(hitA, hitB)
                                                   : tiedEnd(hitA, hitB);
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

size_t countSheets(const Span* s, size_t n) {
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) k += s[i].in.sheet;
    return k;
}

// The index of the first sheet span at or after i, or n.
size_t nextSheet(const Span* s, size_t n, size_t i) {
    while (i < n && !s[i].in.sheet) ++i;
    return i;
}

// A union whose operands hold sheet crossings: the solids merge as always (into the tail of
// out, past room for every sheet), then the sheets are merged in front of them in t order.
// A sheet crossing is kept where no solid span covers or touches it (within the coincidence
// slack: a surface inside a solid is hidden) and once among coincident ones (the left
// operand's, by the tie-break).
size_t mergeWithSheets(const Span* a, size_t na, const Span* b, size_t nb, size_t sheets, Span* out,
                       double originScale) {
    size_t read = sheets;
    const size_t end =
        sheets + mergeSolid<SetOp::Union, true>(a, na, b, nb, out + sheets, originScale);
    size_t write = 0;  // never reaches read: fewer sheets are written than there is room for
    size_t ia = nextSheet(a, na, 0), ib = nextSheet(b, nb, 0);
    while (ia < na || ib < nb) {
        const bool fromA = ib >= nb || (ia < na && a[ia].in.t <= b[ib].in.t);
        const Span& sheet = fromA ? a[ia] : b[ib];
        if (fromA)
            ia = nextSheet(a, na, ia + 1);
        else
            ib = nextSheet(b, nb, ib + 1);
        const double t = sheet.in.t;
        while (read < end &&
               out[read].out.t < t - coincidenceSlack(originScale, out[read].out.t, t))
            out[write++] = out[read++];
        if (read < end && out[read].in.t <= t + coincidenceSlack(originScale, out[read].in.t, t))
            continue;  // covered by a solid
        if (write > 0 && out[write - 1].in.sheet &&
            t - out[write - 1].in.t <= coincidenceSlack(originScale, out[write - 1].in.t, t))
            continue;  // the same crossing as the previous sheet's
        out[write++] = sheet;
    }
    while (read < end) out[write++] = out[read++];
    return write;
}

// mergeSolid for an operation known only at run time.
template <bool SkipSheets>
size_t mergeSolidFor(SetOp op, const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                     double originScale) {
    switch (op) {
        case SetOp::Union:
            if (!SkipSheets && na == 1 && nb == 1) return uniteSingle(a[0], b[0], out, originScale);
            return mergeSolid<SetOp::Union, SkipSheets>(a, na, b, nb, out, originScale);
        case SetOp::Intersection:
            if (!SkipSheets && na == 1 && nb == 1)
                return intersectSingle(a[0], b[0], out, originScale);
            return mergeSolid<SetOp::Intersection, SkipSheets>(a, na, b, nb, out, originScale);
        case SetOp::Difference:
            if (!SkipSheets && na == 1 && nb == 1)
                return subtractSingle(a[0], b[0], out, originScale);
            return mergeSolid<SetOp::Difference, SkipSheets>(a, na, b, nb, out, originScale);
    }
    return 0;
}

}  // namespace

size_t mergeSpans(SetOp op, const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                  double originScale) {
    // Sheets only ever meet unions (compile rejects them under difference and intersection;
    // were one there, it would enclose nothing and vanish). A union's operands were just
    // counted: without sheets, the cursors need not look for them again.
    if (op == SetOp::Union) {
        const size_t sheets = countSheets(a, na) + countSheets(b, nb);
        if (sheets > 0) return mergeWithSheets(a, na, b, nb, sheets, out, originScale);
        return mergeSolid<SetOp::Union, false>(a, na, b, nb, out, originScale);
    }
    return mergeSolidFor<true>(op, a, na, b, nb, out, originScale);
}

size_t mergeSolidSpans(SetOp op, const Span* a, size_t na, const Span* b, size_t nb, Span* out,
                       double originScale) {
    return mergeSolidFor<false>(op, a, na, b, nb, out, originScale);
}

}  // namespace csg
