// The three queries. Notation: see csg/Span.h. Every evaluation pushes the spans of one node,
// clipped to a parameter range [t0, t1], onto the context's span stack and returns how many it
// pushed; intermediate lists live on that stack, so a query allocates nothing once the stack
// has grown to the deepest ray seen.
#include <algorithm>
#include <cmath>

#include "csg/Bvh.h"
#include "csg/Compiled.h"
#include "csg/Scene.h"
#include "csg/SpanList.h"
#include "primitives/base/Grid.h"
#include "primitives/solvers/LinePoint.h"

namespace csg {

// One query of one ray over the compiled tree: the span lists of its nodes, merged bottom-up
// (spans), or the first crossing (closest), or any solid (any), with every shortcut below.
struct SpanWalk {
    const Scene& scene;
    QueryContext& ctx;
    const Ray& ray;
    SlabRay slab;
    double originScale;   // |o| / |d|: see tol::kCoincidentRel
    double originLength;  // |o|, and 1 / |d|^2: for missesBall
    double invDD;
    unsigned octant;  // bit a: d[a] < 0 (BvhNode::order)

    SpanWalk(const Scene& s, QueryContext& c, const Ray& r)
        : scene(s), ctx(c), ray(r), slab(r.o, r.d), octant(octantOf(r.d)) {
        const double dLength = glm::length(r.d);
        originLength = glm::length(r.o);
        originScale = dLength > 0.0 ? originLength / dLength : 0.0;
        invDD = 1.0 / glm::dot(r.d, r.d);
        if (!s.slabs_.empty()) {
            for (int i = 0; i < 4; ++i)
                slabAlpha[i] = glm::dot(kSlabNormals[i], r.o),
                slabInvD[i] = 1.0 / glm::dot(kSlabNormals[i], r.d);
            slabOriginMargin = tol::kBallMarginRel * std::sqrt(3.0) * originLength;
        }
    }

    // The ray against the slab polyhedra (DiagonalSlabs), formed once: n . o, 1 / (n . d), and
    // the ray's share of the rounding allowance (n . o errs by a few ulps of |n| |o|).
    double slabAlpha[4], slabInvD[4], slabOriginMargin = 0.0;

    // The span stack: ctx.stack_[0, top) is in use. The vector only grows (its size is the
    // high-water mark), so pushing never value-initializes spans in the steady state.
    size_t top = 0;
    std::vector<Span>& stack() { return ctx.stack_; }

    // Room for n more spans at top; invalidates pointers into the stack taken before.
    Span* room(size_t n) {
        if (stack().size() < top + n) stack().resize(std::max(top + n, 2 * stack().size()));
        return stack().data() + top;
    }

    // Does the ray within [t0, t1] meet the node's bounds?
    bool touches(const Bounds3& box, double t0, double t1) {
        ++ctx.stats.nodeVisits;
        return clipToBox(slab, box, t0, t1);
    }

    // Does the ray's line pass outside the ball, by the margin of tol::kBallMarginRel? From the
    // point of the line nearest the centre; false for a degenerate ray (NaN compares false).
    bool missesBall(const BoundingBall& b) const {
        const Vec3 oc = b.center - ray.o;
        const Vec3 nearest = ray.o + (glm::dot(oc, ray.d) * invDD) * ray.d;
        const Vec3 off = b.center - nearest;
        const double reach = b.radius + tol::kBallMarginRel * (originLength + b.size);
        return glm::dot(off, off) > reach * reach;
    }

    // Does the ray within [t0, t1] pass outside the slab polyhedron, each plane pushed out by
    // tol::kBallMarginRel of the ray's origin and the planes' size (the ball's rule)? Each pair
    // of planes clips [t0, t1] as a box's slab does; a NaN (0 * inf: the ray in a plane) never
    // replaces a bound, as in clipToBox.
    bool missesSlabs(const DiagonalSlabs& s, double t0, double t1) const {
        const double margin = slabOriginMargin + s.margin;
        for (int i = 0; i < 4; ++i) {
            double tNear = (s.lo[i] - margin - slabAlpha[i]) * slabInvD[i];
            double tFar = (s.hi[i] + margin - slabAlpha[i]) * slabInvD[i];
            if (tNear > tFar) std::swap(tNear, tFar);
            t0 = tNear > t0 ? tNear : t0;
            t1 = tFar < t1 ? tFar : t1;
        }
        return t0 > t1;
    }

    // May the ray within [t0, t1] meet the node: its bounds (unless implied), then its ball,
    // then its slab polyhedron?
    bool mayMeet(const CompiledNode& node, double t0, double t1) {
        if (!node.boundsImplied && !touches(node.bounds, t0, t1)) return false;
        if (node.ball != kNoNode && missesBall(scene.balls_[node.ball])) return false;
        if (node.slabs == kNoNode || !missesSlabs(scene.slabs_[node.slabs], t0, t1)) return true;
        ++ctx.stats.slabCulls;
        return false;
    }

    size_t eval(uint32_t index, double t0, double t1) {
        const CompiledNode& node = scene.nodes_[index];
        if (!mayMeet(node, t0, t1)) return 0;
        switch (node.kind) {
            case Op::Leaf:
                return evalLeaf(scene.leaves_[node.first], node.first, t0, t1);
            case Op::Union:
                return evalUnion(node, t0, t1);
            case Op::Intersection:
            case Op::Difference:
                return evalCut(node, t0, t1);
        }
        return 0;
    }

    // The ray in the frame group last entered (LeafGeometry::frame), and 1 / its d; arrays, so
    // that a leaf's permutation indexes them directly.
    uint32_t group = kNoNode;
    double groupO[3], groupD[3], groupInvD[3];

    void enterGroup(uint32_t frame) {
        group = frame;
        // The world frame (parts placed without a transform): the ray as it is, and the slab
        // ray's 1 / d, the values the identity matrix and the divisions give (but for the sign
        // of a zero component, which the matrix's sums make +0).
        if (scene.worldFrames_[frame]) {
            for (int i = 0; i < 3; ++i) {
                groupO[i] = ray.o[i];
                groupD[i] = ray.d[i];
                groupInvD[i] = slab.invD[i];
            }
            return;
        }
        const Affine& m = scene.frameFromWorld_[frame];
        const Vec3 o = transformPoint(m, ray.o), d = transformVector(m, ray.d);
        for (int i = 0; i < 3; ++i) {
            groupO[i] = o[i];
            groupD[i] = d[i];
            groupInvD[i] = 1.0 / d[i];
        }
    }

    struct LocalRay {
        Vec3 o, d, invD;
    };

    // The leaves solved in this query, one slot per leaf index modulo kSolvedSlots (a leaf
    // evicts only a leaf of its own slot). A query meets a leaf twice when closest() takes the
    // list of an object a ray starts inside whose exit it does not have yet (exitAlone), or
    // falls back to the root's list: that walks the leaves closest() has just solved.
    static constexpr uint32_t kSolvedSlots = 4;
    // Set while closest() evaluates a top-level object that is one leaf, and while any()
    // evaluates a leaf: they read only its first span past t0 (see evalLeaf).
    bool firstSpanOnly = false;
    static constexpr double kFirstSpanSlacks = 1e3;  // LocalSpans::margin, in sliver slacks
    struct Solved {
        uint32_t leaf = kNoNode;
        LocalSpans spans;
    };
    Solved solved[kSolvedSlots];

    // The ray in the leaf's frame: by a matrix into its frame group once per run of leaves of
    // that group (a part's leaves mostly share one), then by the leaf's exact axis permutation
    // (the reciprocal of -x is -(1 / x), so permuting 1 / d is exact); d keeps its length so t
    // is unchanged.
    LocalRay toLeafFrame(const LeafGeometry& leaf) {
        if (leaf.frame != group) enterGroup(leaf.frame);
        if (!leaf.permuted)
            return {Vec3(groupO[0], groupO[1], groupO[2]), Vec3(groupD[0], groupD[1], groupD[2]),
                    Vec3(groupInvD[0], groupInvD[1], groupInvD[2])};
        const uint8_t* a = leaf.axis;
        const double* s = leaf.sign;
        return {Vec3(s[0] * groupO[a[0]] + leaf.offset.x, s[1] * groupO[a[1]] + leaf.offset.y,
                     s[2] * groupO[a[2]] + leaf.offset.z),
                Vec3(s[0] * groupD[a[0]], s[1] * groupD[a[1]], s[2] * groupD[a[2]]),
                Vec3(s[0] * groupInvD[a[0]], s[1] * groupInvD[a[1]], s[2] * groupInvD[a[2]])};
    }

    size_t evalLeaf(const LeafGeometry& leaf, uint32_t leafIndex, double t0, double t1) {
        const LocalRay leafRay = toLeafFrame(leaf);
        const Vec3 &o = leafRay.o, &d = leafRay.d;
        // Solve near the primitive: restart the ray where it enters the local bounds.
        double b0 = -kInfinity, b1 = kInfinity;
        if (!clipToBox(SlabRay(o, leafRay.invD, SlabRay::Reciprocal{}), leaf.localBounds, b0, b1) ||
            b1 < t0 || b0 > t1)
            return 0;
        const double shift = std::isfinite(b0) ? b0 : (std::isfinite(b1) ? b1 : 0.0);

        // The leaf's spans along the whole line depend on the ray only, not on [t0, t1]: a
        // leaf met again in this query takes them from its slot instead of being solved again.
        // The spans are clipped at t0 (`from`, LocalSpans): a slot solved from no later than
        // that serves. They are clipped at t1 too (`to`), and a primitive that left out what
        // lies past it (cutAtTo: a twisted extrusion, whose solve grows with the chord) serves
        // only up to its own `to`. closest() on a leaf that is a whole object reads only its
        // first span past t0, and of that span only where it begins (firstOnly: its end may
        // come early); such a list is not whole, so it is not kept for another visit. Margin: a
        // thousand sliver slacks of the span ends the leaf's box allows.
        const double from = t0 - shift, to = t1 - shift;
        Solved& slot = solved[leafIndex % kSolvedSlots];
        if (slot.leaf != leafIndex || slot.spans.from > from ||
            (slot.spans.cutAtTo && slot.spans.to < to)) {
            ++ctx.stats.primitiveTests;
            const bool bounded = std::isfinite(b0) && std::isfinite(b1);
            const bool firstOnly = firstSpanOnly && bounded;
            slot.leaf = firstOnly ? kNoNode : leafIndex;
            slot.spans.count = 0;
            slot.spans.sheet = false;
            slot.spans.firstOnly = firstOnly;
            slot.spans.from = bounded ? from : -kInfinity;
            slot.spans.to = bounded ? to : kInfinity;
            slot.spans.cutAtTo = false;
            slot.spans.margin =
                bounded
                    ? kFirstSpanSlacks *
                          coincidenceSlack(originScale, std::abs(t0) + std::abs(b0), std::abs(b1))
                    : 0.0;
            const Vec3 start = pointOnLine(o, d, shift);
            std::visit([&](const auto& shape) { shape.spans(start, d, slot.spans); }, leaf.shape);
        }
        const LocalSpans& local = slot.spans;

        // A sheet's crossings are zero-length spans by nature: clipped, never regularized away.
        const size_t base = top;
        if (local.sheet) {
            Span* out = room(local.count);
            size_t n = 0;
            for (int i = 0; i < local.count; ++i) {
                const Hit h{local.entries[i].tIn + shift, leafIndex, local.entries[i].faceIn, false,
                            true};
                if (h.t >= t0 && h.t <= t1) out[n++] = {h, h};
            }
            top = base + n;
            return n;
        }
        // Clip to [t0, t1] and regularize; a primitive yields at most LocalSpans::kCapacity.
        SpanWriter writer(room(local.count), originScale);
        for (int i = 0; i < local.count; ++i) {
            const LocalSpans::Entry& e = local.entries[i];
            Span s{{e.tIn + shift, leafIndex, e.faceIn, false},
                   {e.tOut + shift, leafIndex, e.faceOut, false}};
            if (s.in.t < t0) s.in = {t0, leafIndex, kClipFace, false};
            if (s.out.t > t1) s.out = {t1, leafIndex, kClipFace, false};
            if (s.in.t <= s.out.t) writer.emit(s);
        }
        top = base + writer.count();
        return writer.count();
    }

    // Merges the list at [base, base + na) with the one right after it (nb spans) and leaves
    // the result at base. Returns its length.
    size_t mergeInPlace(SetOp op, size_t base, size_t na, size_t nb) {
        top = base + na + nb;
        Span* out = room(na + nb);
        Span* s = stack().data();
        // Without sheets in the scene (known at compile), skip mergeSpans' scan for them.
        const size_t n =
            scene.hasSheets_
                ? mergeSpans(op, s + base, na, s + base + na, nb, out, originScale)
                : mergeSolidSpans(op, s + base, na, s + base + na, nb, out, originScale);
        // Most results are a span or two: copy those field by field (they were just written
        // so, see SpanWriter::emit), not by a memmove call.
        if (n <= 2) {
            for (size_t i = 0; i < n; ++i) {
                storeHit(s[base + i].in, out[i].in);
                storeHit(s[base + i].out, out[i].out);
            }
        } else {
            std::copy(out, out + n, s + base);
        }
        top = base + n;
        return n;
    }

    size_t evalCut(const CompiledNode& node, double t0, double t1) {
        const size_t base = top;
        const size_t na = eval(node.first, t0, t1);
        return na == 0 ? 0 : finishCut(node, base, na);
    }

    // evalCut once the left operand's na > 0 spans are at base.
    size_t finishCut(const CompiledNode& node, size_t base, size_t na) {
        // The right operand matters only where the left one is: narrow its range to that hull.
        const double lo = stack()[base].in.t, hi = stack()[base + na - 1].out.t;
        const size_t nb = eval(node.second, lo, hi);
        if (node.kind == Op::Difference) {
            return nb == 0 ? na : mergeInPlace(SetOp::Difference, base, na, nb);
        }
        if (nb == 0) {
            top = base;
            return 0;
        }
        return mergeInPlace(SetOp::Intersection, base, na, nb);
    }

    // A difference's result without its right operand B solved, from boxes only: where along
    // the ray can each of B's operands be? Each one's box (a leaf's local box, the one
    // evalLeaf clips to, or a node's bounds) gives a conservative interval of t.
    struct Reach {
        double t0, t1;
    };
    static constexpr uint32_t kMaxReaches = 8;  // a longer union counts as one box

    bool reach(uint32_t index, double t0, double t1, Reach& r) {
        const CompiledNode& node = scene.nodes_[index];
        r = {t0, t1};
        if (node.kind != Op::Leaf) return clipToBox(slab, node.bounds, r.t0, r.t1);
        const LeafGeometry& leaf = scene.leaves_[node.first];
        const LocalRay local = toLeafFrame(leaf);
        return clipToBox(SlabRay(local.o, local.invD, SlabRay::Reciprocal{}), leaf.localBounds,
                         r.t0, r.t1);
    }

    // With the left operand's na > 0 spans at base: does a piece of them (of the first span's
    // start only, when atStart) lie outside every reach of the right operand's operands, by the
    // margin of tol::kUncoveredPieceSlacks? Then the difference is not empty, and its first
    // span begins with the left operand's first span (same Hit), without solving the right.
    bool uncovered(uint32_t right, size_t base, size_t na, bool atStart) {
        const Span* a = stack().data() + base;
        const double lo = a[0].in.t, hi = a[na - 1].out.t;
        const double slack = coincidenceSlack(originScale, lo, hi);
        const double minPiece = tol::kUncoveredPieceSlacks * slack;
        // The operands whose boxes count: a short union's children (not through its BVH), else
        // the right operand itself as one box.
        const CompiledNode& b = scene.nodes_[right];
        const bool byOperand = b.kind == Op::Union && !b.structured() && b.count <= kMaxReaches;
        const uint32_t operands = byOperand ? b.count : 1;
        const auto operand = [&](uint32_t k) {
            return byOperand ? scene.children_[b.first + k] : right;
        };
        Reach r;
        if (atStart) {
            // Only the first piece counts: A's first span must reach past start + minPiece,
            // and no operand's box, widened by a slack, may begin before that, i.e. none may
            // meet [start, clear]. Stops at the first one that does; nothing to sort. For a
            // ray that starts inside A, the piece is the whole first span, whose end is then
            // the node's too (closest() hands it to exitAlone).
            const double start = a[0].in.t;
            const double clear = (a[0].in.isSurface() ? start + minPiece : a[0].out.t) + slack;
            if (!(a[0].out.t - start > minPiece)) return false;
            for (uint32_t k = 0; k < operands; ++k)
                if (reach(operand(k), start, clear, r)) return false;
            return true;
        }
        Reach covers[kMaxReaches];
        uint32_t n = 0;
        for (uint32_t k = 0; k < operands; ++k)
            if (reach(operand(k), lo, hi, r)) covers[n++] = {r.t0 - slack, r.t1 + slack};
        // Ascending by start, then overlapping covers fused: disjoint and ascending.
        for (uint32_t i = 1; i < n; ++i)
            for (uint32_t j = i; j > 0 && covers[j].t0 < covers[j - 1].t0; --j)
                std::swap(covers[j], covers[j - 1]);
        uint32_t m = 0;
        for (uint32_t i = 0; i < n; ++i) {
            if (m > 0 && covers[i].t0 <= covers[m - 1].t1)
                covers[m - 1].t1 = std::max(covers[m - 1].t1, covers[i].t1);
            else
                covers[m++] = covers[i];
        }
        // The gaps between covers (before the first, after the last) against A's spans.
        double gapStart = -kInfinity;
        size_t i = 0;
        for (uint32_t c = 0; c <= m; ++c) {
            const double gapEnd = c < m ? covers[c].t0 : kInfinity;
            while (i < na && a[i].out.t <= gapStart) ++i;
            for (size_t k = i; k < na && a[k].in.t < gapEnd; ++k)
                if (std::min(a[k].out.t, gapEnd) - std::max(a[k].in.t, gapStart) > minPiece)
                    return true;
            if (c < m) gapStart = covers[c].t1;
        }
        return false;
    }

    // Pushes the node's list, or, for a difference whose left operand sticks out of every box
    // of its right operand (uncovered()), the left operand's list, without solving the right:
    // empty exactly when the node's list is, and when atStart, its first span begins where the
    // node's does, and ends where the node's does when it begins at t0 (a ray that starts
    // inside). What any() (atStart false) and closest() need.
    size_t evalShortcut(uint32_t index, double t0, double t1, bool atStart) {
        const CompiledNode& node = scene.nodes_[index];
        if (node.kind != Op::Difference) return eval(index, t0, t1);
        if (!mayMeet(node, t0, t1)) return 0;
        const size_t base = top;
        const size_t na = eval(node.first, t0, t1);
        if (na == 0) return 0;
        return uncovered(node.second, base, na, atStart) ? na : finishCut(node, base, na);
    }

    // Calls visit(child) for the union's children whose bounds the ray meets in [t0, t1],
    // nearer BVH slots first; visit returns false to stop, and may lower t1 through the
    // reference it is given.
    template <class Visit>
    void forEachChild(const CompiledNode& node, double t0, double& t1, Visit&& visit) {
        const std::vector<uint32_t>& children = scene.children_;
        if (node.grid != kNoNode) {
            const bool going = node.halving
                                   ? walkHalvingGrid(scene.halvingGrids_[node.grid], t0, t1, visit)
                                   : walkGrid(scene.grids_[node.grid], t0, t1, visit);
            if (!going) return;
        } else if (node.bvhRoot == kNoNode) {
            for (uint32_t i = 0; i < node.bounded; ++i)
                if (!visit(children[node.first + i])) return;
        } else if (!walkBvh(node.bvhRoot, t0, t1, visit)) {
            return;
        }
        for (uint32_t i = node.bounded; i < node.count; ++i)
            if (!visit(children[node.first + i])) return;
    }

    // A BVH slot the walk has yet to enter: a node (leafCount 0) or a leaf's children.
    struct PendingSlot {
        double tNear;  // its box's widened entry: nothing in it lies before
        uint32_t target;
        uint32_t leafCount;
    };

    // forEachChild's walk of the BVH: the slots of a node are tested at once and pushed far to
    // near, so the nearest is entered next; a slot whose entry lies past t1 (lowered by visit
    // since it was pushed) is dropped unopened. False when visit stopped the walk.
    template <class Visit>
    bool walkBvh(uint32_t root, double t0, double& t1, Visit& visit) {
        // Each node pops one entry and pushes at most four: depth grows the stack by three.
        PendingSlot todo[3 * kBvhMaxDepth + 4];
        int pending = 0;
        const BvhNode* b = &scene.bvh_[root];
        for (;;) {
            ctx.stats.nodeVisits += b->slots;
            alignas(32) double near[4];
            const unsigned hits = clipToBoxes(slab, b->boxes, t0, t1, near) & b->usedMask();
            // The slots hit, farthest first, so the nearest is popped next.
            const unsigned order = b->order[octant];
            for (int i = b->slots - 1; i >= 0; --i) {
                const unsigned k = order >> (2 * i) & 3u;
                if (hits >> k & 1u) todo[pending++] = {near[k], b->slot[k], b->leafCount[k]};
            }
            // Pop until a node to enter, visiting the leaves on the way.
            for (;;) {
                if (pending == 0) return true;
                const PendingSlot& entry = todo[--pending];
                if (entry.tNear > t1) continue;
                if (entry.leafCount == 0) {
                    b = &scene.bvh_[entry.target];
                    break;
                }
                const uint32_t first = entry.target, count = entry.leafCount;
                for (uint32_t i = 0; i < count; ++i)
                    if (!visit(scene.children_[first + i])) return false;
            }
        }
    }

    // A new walk number for the grids' mailbox (QueryContext::stamp_), its stamps sized to the
    // scene; on the counter's wrap every stamp is cleared once.
    uint32_t startWalk() {
        if (ctx.stamp_.size() < scene.children_.size()) ctx.stamp_.resize(scene.children_.size());
        if (++ctx.walks_ == 0) {
            std::fill(ctx.stamp_.begin(), ctx.stamp_.end(), 0u);
            ctx.walks_ = 1;
        }
        return ctx.walks_;
    }

    // Visits the children a grid cell lists that this walk has not visited yet. The mailbox
    // evaluates a child listed by many cells once, over the whole [t0, t1]; a hit it has
    // beyond the current cell lowers t1, and the walk goes on through the cells that begin
    // before that hit: so a hit is final only once no earlier cell is left (the lecture's
    // "a hit counts only inside the current cell", without testing the child again).
    template <class Visit>
    bool visitCell(const uint32_t* items, uint32_t count, uint32_t walk, Visit& visit) {
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t position = items[i];
            if (ctx.stamp_[position] == walk) continue;
            ctx.stamp_[position] = walk;
            if (!visit(scene.children_[position])) return false;
        }
        return true;
    }

    // The ray's range [tIn, tOut] inside a grid's box within [t0, t1], or false. (A range
    // with an infinite end, from a zero direction, has no cell to start in: walkGrid then
    // visits every child the grid lists, each once.)
    bool enterGrid(const Bounds3& box, double t0, double t1, double& tIn, double& tOut) {
        tIn = t0;
        tOut = t1;
        return clipToBox(slab, box, tIn, tOut);
    }

    // forEachChild's walks of the grids (primitives/base/Grid.h) from the cell where the ray
    // enters the box until past t1 (lowered by visit) or out of the box. False when visit
    // stopped the walk. Out of line: inlined, they changed how the BVH walk's callers inline
    // (+0.55 % instructions on csg_grid, which has no grid), and a call per grid walk is
    // nothing beside the walk.
    template <class Visit>
    [[gnu::noinline]] bool walkGrid(const UniformGrid& g, double t0, double& t1, Visit& visit) {
        double tIn, tOut;
        if (!enterGrid(g.box, t0, t1, tIn, tOut)) return true;
        const uint32_t walk = startWalk();
        if (!std::isfinite(tIn) || !std::isfinite(tOut))
            return visitCell(g.items.data(), static_cast<uint32_t>(g.items.size()), walk, visit);
        return walkUniformGrid(g, ray.o, ray.d, slab.invD, tIn, tOut, t1, ctx.stats.nodeVisits,
                               [&](const uint32_t* items, uint32_t count) {
                                   return visitCell(items, count, walk, visit);
                               });
    }

    template <class Visit>
    [[gnu::noinline]] bool walkHalvingGrid(const HalvingGrid& g, double t0, double& t1,
                                           Visit& visit) {
        double tIn, tOut;
        if (!enterGrid(g.box, t0, t1, tIn, tOut)) return true;
        const uint32_t walk = startWalk();
        return csg::walkHalvingGrid(g, ray.o, slab.invD, tIn, tOut, t1, ctx.stats.nodeVisits,
                                    [&](const uint32_t* items, uint32_t count) {
                                        return visitCell(items, count, walk, visit);
                                    });
    }

    size_t evalUnion(const CompiledNode& node, double t0, double t1) {
        const size_t base = top;
        size_t n = 0;
        forEachChild(node, t0, t1, [&](uint32_t child) {
            const size_t nb = eval(child, t0, t1);
            if (nb > 0) n = n == 0 ? nb : mergeInPlace(SetOp::Union, base, n, nb);
            return true;
        });
        return n;
    }

    // Is any span of positive length inside [t0, t1]? A union is non-empty when any child is.
    bool any(uint32_t index, double t0, double t1) {
        const CompiledNode& node = scene.nodes_[index];
        if (node.kind == Op::Union) {
            if (!node.boundsImplied && !touches(node.bounds, t0, t1)) return false;
            bool found = false;
            forEachChild(node, t0, t1,
                         [&](uint32_t child) { return !(found = any(child, t0, t1)); });
            return found;
        }
        // A leaf's list is non-empty exactly when its first span past t0 that is longer than
        // LocalSpans::margin, or one before it, survives the clipping at t1 (a later span
        // starts past that one), so the first span is all it needs to solve (firstOnly). An end
        // given early that still leaves the span longer than the margin past t0 survives the
        // clipping exactly when the true end does.
        const size_t base = top;
        firstSpanOnly = node.kind == Op::Leaf;
        const size_t n = evalShortcut(index, t0, t1, false);
        firstSpanOnly = false;
        top = base;
        return n > 0;
    }

    // any() over the root with the cached top-level object tried first; a union's answer is
    // the OR of its children's, so the order changes only when the search stops.
    bool anyCached(ObjectCache& cache) {
        const CompiledNode& root = scene.nodes_[scene.root_];
        const double t0 = ray.tmin;
        double t1 = ray.tmax;
        if (root.kind != Op::Union) return any(scene.root_, t0, t1);
        // (The cached object is not reached through the BVH here, so its own bounds are tested
        // even where the BVH leaf's test implies them.)
        if (cache.node != kNoNode && touches(scene.nodes_[cache.node].bounds, t0, t1) &&
            any(cache.node, t0, t1))
            return true;
        if (!root.boundsImplied && !touches(root.bounds, t0, t1)) return false;
        bool found = false;
        forEachChild(root, t0, t1, [&](uint32_t child) {
            if (child == cache.node || !any(child, t0, t1)) return true;
            cache.node = child;
            return !(found = true);
        });
        return found;
    }

    // For a ray that starts inside the top-level object `inside`: the end of that object's
    // first span, when no other object has solid within tol::kExitWindowSlacks coincidence
    // slacks of it. The root union's first span then starts at the ray's start and ends there, with
    // that very hit: every other object's spans near the ray lie inside it or begin past it
    // by more than the slack, the widest gap the union closes. The whole list's answer
    // without merging every object's list into it (a refracted ray inside glass). knownEnd:
    // that end when closest() has it already, else the object is evaluated again (its leaves'
    // lists come from their slots). Empty where the whole list must decide.
    // Out of line: inlined, it moved closest()'s BVH walk out of Scene::closest into calls of
    // their own (+1.8 % instructions on csg_grid, which never starts inside an object).
    [[gnu::noinline]] std::optional<Hit> exitAlone(uint32_t inside,
                                                   const std::optional<Hit>& knownEnd) {
        Hit exit;
        if (knownEnd) {
            exit = *knownEnd;
        } else {
            const size_t base = top;
            const size_t n = eval(inside, ray.tmin, ray.tmax);
            top = base;
            if (n == 0 || stack()[base].in.isSurface() || !stack()[base].out.isSurface())
                return std::nullopt;
            exit = stack()[base].out;
        }
        const double window =
            tol::kExitWindowSlacks * coincidenceSlack(originScale, exit.t, exit.t);
        const double lo = exit.t - window;
        double hi = exit.t + window;
        bool alone = true;
        forEachChild(scene.nodes_[scene.root_], lo, hi, [&](uint32_t child) {
            return child == inside || (alone = !any(child, lo, hi));
        });
        return alone ? std::optional<Hit>(exit) : std::nullopt;
    }

    // First surface end of the root union's spans. Front-to-back over the top-level objects,
    // lowering t1 to the best entry so far, which is exact as long as the ray starts outside
    // every object; a ray that starts inside one takes that object's exit (exitAlone), or
    // else falls back to the whole span list. Always inlined: it is Scene::closest, and the
    // BVH walk inlined into it saves a call per node on csg_grid.
    // t1 stays two coincidence slacks past the best entry: an object entered just before it,
    // or at it, would otherwise be clipped there to a span no longer than the slack, which
    // the span writer drops as a sliver, and a later entry, or the first object met of several
    // entered at one t, would win (a face of the exact rounded box, entered 2e-8 before the
    // edge cylinder under it, lost so, and the hit point inside the face's prism shadowed
    // itself).
    [[gnu::always_inline]] std::optional<Hit> closest() {
        const CompiledNode& root = scene.nodes_[scene.root_];
        double t1 = ray.tmax;
        std::optional<Hit> best;
        uint32_t startsInside = kNoNode;  // the object the ray starts in, once one is met
        std::optional<Hit> insideEnd;     // where its first span ends, when that is known
        if (root.boundsImplied || touches(root.bounds, ray.tmin, t1)) {
            forEachChild(root, ray.tmin, t1, [&](uint32_t child) {
                const size_t base = top;
                firstSpanOnly = scene.nodes_[child].kind == Op::Leaf;
                const size_t n = evalShortcut(child, ray.tmin, t1, true);
                firstSpanOnly = false;
                if (n > 0) {
                    const Hit first = stack()[base].in;
                    top = base;
                    if (!first.isSurface()) {
                        // The object's first span ends where this one does (evalShortcut; a
                        // leaf's firstOnly list gives its exact end for a span the ray starts
                        // in), but for one clipped at a lowered t1 (no surface there).
                        startsInside = child;
                        const Hit end = stack()[base].out;
                        if (end.isSurface()) insideEnd = end;
                        return false;
                    }
                    // At one t, the lower leaf, as the union's merge names it (SpanList.h).
                    if (!best || first.t < best->t ||
                        (first.t == best->t && first.leaf < best->leaf)) {
                        best = first;
                        t1 = std::min(ray.tmax, first.t + 2.0 * coincidenceSlack(originScale,
                                                                                 first.t, first.t));
                    }
                }
                return true;
            });
        }
        if (startsInside == kNoNode) return best;
        if (const std::optional<Hit> exit = exitAlone(startsInside, insideEnd)) return exit;
        const size_t base = top;
        const size_t n = eval(scene.root_, ray.tmin, ray.tmax);
        std::optional<Hit> hit;
        for (size_t i = base; i < base + n && !hit; ++i) {
            if (stack()[i].in.isSurface())
                hit = stack()[i].in;
            else if (stack()[i].out.isSurface())
                hit = stack()[i].out;
        }
        top = base;
        return hit;
    }
};

std::span<const Span> Scene::spans(const Ray& ray, QueryContext& ctx) const {
    ++ctx.stats.rays;
    SpanWalk e(*this, ctx, ray);
    const size_t n = e.eval(root_, ray.tmin, ray.tmax);
    return {ctx.stack_.data(), n};
}

std::optional<Hit> Scene::closest(const Ray& ray, QueryContext& ctx) const {
    ++ctx.stats.rays;
    return SpanWalk(*this, ctx, ray).closest();
}

bool Scene::occluded(const Ray& ray, QueryContext& ctx) const {
    ++ctx.stats.rays;
    return SpanWalk(*this, ctx, ray).any(root_, ray.tmin, ray.tmax);
}

bool Scene::occluded(const Ray& ray, QueryContext& ctx, ObjectCache& cache) const {
    ++ctx.stats.rays;
    return SpanWalk(*this, ctx, ray).anyCached(cache);
}

}  // namespace csg
