// The scene description: an immutable binary CSG tree of primitives. Nodes are shared values
// (a part used a thousand times is one subtree), each may carry an affine transform from its
// own frame to its parent's. compile() (csg/Compile.h) turns a tree into a queryable Scene.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "primitives/Primitives.h"
#include "primitives/base/Math.h"

namespace csg {

enum class Op : uint8_t { Leaf, Union, Intersection, Difference };

struct Node;
using NodePtr = std::shared_ptr<const Node>;

// Opaque tags that csg/ carries but never interprets: io/ maps sourceTag to file:line:col
// (so a compile error can name the line) and material to a shading material.
struct Tags {
    uint32_t source = 0;
    uint32_t material = 0;
};

struct Node {
    Op op = Op::Leaf;
    Mat4 parentFromNode{1.0};  // identity unless the node is transformed
    Primitive primitive{};     // leaves only
    NodePtr left, right;       // operators only; difference is left minus right
    Tags tags;
};

// Builders. Each returns a new node; arguments are shared, never copied deeply.
NodePtr leaf(Primitive primitive, Tags tags = {});
NodePtr unite(NodePtr a, NodePtr b, Tags tags = {});
NodePtr intersect(NodePtr a, NodePtr b, Tags tags = {});
NodePtr subtract(NodePtr a, NodePtr b, Tags tags = {});

// n-ary forms built as balanced binary trees (depth log2 n, so 10^6 children neither deepen
// recursion nor slow compile). An empty list gives nullptr, which means the empty solid.
// subtractAll(a, {b, c}) = a - (b u c), OpenSCAD's difference() { a; b; c; }.
NodePtr uniteAll(const std::vector<NodePtr>& parts, Tags tags = {});
NodePtr intersectAll(const std::vector<NodePtr>& parts, Tags tags = {});
NodePtr subtractAll(NodePtr a, const std::vector<NodePtr>& cut, Tags tags = {});

// The node seen through one more transform: parentFromNode becomes m * parentFromNode.
// Singular or non-finite matrices are accepted here and rejected by compile(), which names
// the node's source tag.
NodePtr transformed(const Mat4& m, NodePtr node);

}  // namespace csg
