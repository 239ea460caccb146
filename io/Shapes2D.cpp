#include "io/Shapes2D.h"

#include <unordered_map>

#include "csg/derived/Boundary2D.h"

namespace io {

namespace {

using csg::Extrusion;
using csg::Node;
using csg::NodePtr;

// A copy of the tree with each leaf rebuilt by f, sharing what the original shares.
template <class F>
NodePtr mapLeaves(const NodePtr& node, F& f, std::unordered_map<const Node*, NodePtr>& done) {
    if (!node) return node;
    if (auto it = done.find(node.get()); it != done.end()) return it->second;
    NodePtr result;
    if (node->op == csg::Op::Leaf) {
        result = csg::leaf(f(*node), node->tags);
    } else {
        auto copy = std::make_shared<Node>(*node);
        copy->left = mapLeaves(node->left, f, done);
        copy->right = mapLeaves(node->right, f, done);
        result = std::move(copy);
    }
    done.emplace(node.get(), result);
    return result;
}

}  // namespace

int dimensionOf(const NodePtr& node) {
    const Node* n = node.get();
    while (n && n->op != csg::Op::Leaf) n = n->left ? n->left.get() : n->right.get();
    if (!n) return 0;
    const auto* e = std::get_if<Extrusion>(&n->primitive);
    return e && e->kind == Extrusion::Kind::Plane ? 2 : 3;
}

NodePtr transformed2D(const csg::Mat4& m, const NodePtr& shape) {
    const glm::dmat2 linear(m[0][0], m[0][1], m[1][0], m[1][1]);
    const csg::Vec2 shift(m[3][0], m[3][1]);
    std::unordered_map<const csg::Outline*, std::shared_ptr<const csg::Outline>> outlines;
    auto map = [&](const Node& leaf) {
        Extrusion e = std::get<Extrusion>(leaf.primitive);
        auto& mapped = outlines[e.outline.get()];
        if (!mapped) mapped = std::make_shared<csg::Outline>(e.outline->mapped(linear, shift));
        Extrusion out = Extrusion::plane(mapped, e.shape);
        out.accuracy = e.accuracy;
        return out;
    };
    std::unordered_map<const Node*, NodePtr> done;
    return mapLeaves(shape, map, done);
}

std::optional<BoundaryOutline> boundaryOutline(const csg::Node& shape) {
    const csg::Boundary2D boundary = csg::boundaryOf(csg::Region2D(shape));
    const std::optional<std::vector<csg::Contour2D>> contours = csg::contoursOf(boundary);
    if (!contours) return std::nullopt;
    BoundaryOutline result{std::make_shared<csg::Outline>(), boundary.approximated};
    result.outline->rule = csg::FillRule::NonZero;  // contours that never cross, holes clockwise
    for (const csg::Contour2D& contour : *contours)
        for (const csg::BoundaryPiece& p : contour)
            result.outline->segments.push_back(csg::segmentOf(p));
    return result;
}

NodePtr unitedShape(const NodePtr& shape) {
    if (!shape || shape->op == csg::Op::Leaf) return shape;
    std::optional<BoundaryOutline> united = boundaryOutline(*shape);
    if (!united || united->approximated) return shape;
    if (united->outline->segments.empty()) return NodePtr();
    return csg::leaf(Extrusion::plane(std::move(united->outline), "union"), shape->tags);
}

NodePtr liftLeaves(const NodePtr& shape, const std::function<Extrusion(const Extrusion&)>& lift) {
    auto map = [&](const Node& leaf) { return lift(std::get<Extrusion>(leaf.primitive)); };
    std::unordered_map<const Node*, NodePtr> done;
    return mapLeaves(shape, map, done);
}

}  // namespace io
