#include "csg/Tree.h"

namespace csg {
namespace {

NodePtr binary(Op op, NodePtr a, NodePtr b, Tags tags) {
    auto n = std::make_shared<Node>();
    n->op = op;
    n->left = std::move(a);
    n->right = std::move(b);
    n->tags = tags;
    return n;
}

// Balanced fold of parts[lo, hi) under op; nullptr entries (empty solids) are skipped by the
// callers before folding.
NodePtr fold(Op op, const std::vector<NodePtr>& parts, size_t lo, size_t hi, Tags tags) {
    if (hi - lo == 1) return parts[lo];
    const size_t mid = lo + (hi - lo) / 2;
    return binary(op, fold(op, parts, lo, mid, tags), fold(op, parts, mid, hi, tags), tags);
}

}  // namespace

NodePtr leaf(Primitive primitive, Tags tags) {
    auto n = std::make_shared<Node>();
    n->op = Op::Leaf;
    n->primitive = primitive;
    n->tags = tags;
    return n;
}

NodePtr unite(NodePtr a, NodePtr b, Tags tags) {
    if (!a) return b;
    if (!b) return a;
    return binary(Op::Union, std::move(a), std::move(b), tags);
}

NodePtr intersect(NodePtr a, NodePtr b, Tags tags) {
    if (!a || !b) return nullptr;
    return binary(Op::Intersection, std::move(a), std::move(b), tags);
}

NodePtr subtract(NodePtr a, NodePtr b, Tags tags) {
    if (!a || !b) return a;
    return binary(Op::Difference, std::move(a), std::move(b), tags);
}

NodePtr uniteAll(const std::vector<NodePtr>& parts, Tags tags) {
    std::vector<NodePtr> present;
    for (const NodePtr& p : parts)
        if (p) present.push_back(p);
    return present.empty() ? nullptr : fold(Op::Union, present, 0, present.size(), tags);
}

NodePtr intersectAll(const std::vector<NodePtr>& parts, Tags tags) {
    for (const NodePtr& p : parts)
        if (!p) return nullptr;
    return parts.empty() ? nullptr : fold(Op::Intersection, parts, 0, parts.size(), tags);
}

NodePtr subtractAll(NodePtr a, const std::vector<NodePtr>& cut, Tags tags) {
    return subtract(std::move(a), uniteAll(cut, tags), tags);
}

NodePtr transformed(const Mat4& m, NodePtr node) {
    if (!node) return nullptr;
    auto n = std::make_shared<Node>(*node);
    n->parentFromNode = m * node->parentFromNode;
    return n;
}

}  // namespace csg
