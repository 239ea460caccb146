// Test support: seeded random CSG trees and the independent point-membership oracle that
// classifies a point against the *uncompiled* tree with the primitives' inside tests.
#pragma once

#include <random>

#include "csg/Tree.h"

namespace csg::testing {

// Is world point p inside the solid of `node` placed by worldFromParent?
inline bool insideTree(const Node* node, const Mat4& worldFromParent, const Vec3& p) {
    if (!node) return false;
    const Mat4 worldFromNode = worldFromParent * node->parentFromNode;
    switch (node->op) {
        case Op::Leaf: {
            const Vec3 local = transformPoint(glm::inverse(worldFromNode), p);
            return std::visit([&](const auto& s) { return s.inside(local); }, node->primitive);
        }
        case Op::Union:
            return insideTree(node->left.get(), worldFromNode, p) ||
                   insideTree(node->right.get(), worldFromNode, p);
        case Op::Intersection:
            return insideTree(node->left.get(), worldFromNode, p) &&
                   insideTree(node->right.get(), worldFromNode, p);
        case Op::Difference:
            return insideTree(node->left.get(), worldFromNode, p) &&
                   !insideTree(node->right.get(), worldFromNode, p);
    }
    return false;
}

inline bool insideTree(const NodePtr& root, const Vec3& p) {
    return insideTree(root.get(), Mat4(1.0), p);
}

// A random affine map: rotation about a random axis, scale in [0.5, 2] per axis, a shear of
// up to 0.3 and a translation within [-1, 1]^3.
inline Mat4 randomAffine(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0), s(0.5, 2.0), a(0.0, 360.0);
    Vec3 axis(u(rng), u(rng), u(rng));
    if (glm::length(axis) < 1e-3) axis = Vec3(0, 0, 1);
    Mat4 m = glm::translate(Mat4(1.0), Vec3(u(rng), u(rng), u(rng)));
    m = glm::rotate(m, glm::radians(a(rng)), glm::normalize(axis));
    Mat4 shear(1.0);
    shear[1][0] = 0.3 * u(rng);
    shear[2][1] = 0.3 * u(rng);
    return glm::scale(m * shear, Vec3(s(rng), s(rng), s(rng)));
}

// A random primitive of unit-ish size around the origin.
inline Primitive randomPrimitive(std::mt19937_64& rng, bool allowHalfSpace) {
    std::uniform_real_distribution<double> u(0.3, 1.2);
    switch (std::uniform_int_distribution<int>(0, allowHalfSpace ? 4 : 3)(rng)) {
        case 0:
            return Sphere{u(rng)};
        case 1:
            return Box{Vec3(-u(rng), -u(rng), -u(rng)), Vec3(u(rng), u(rng), u(rng))};
        case 2:
            return Cylinder{2 * u(rng), u(rng), u(rng)};
        case 3: {  // a cone, apex up or down
            const bool apexUp = std::uniform_int_distribution<int>(0, 1)(rng);
            const double r = u(rng);
            return Cylinder{2 * u(rng), apexUp ? r : 0.0, apexUp ? 0.0 : r};
        }
        default:
            return HalfSpace{Vec3(u(rng) - 0.75, u(rng) - 0.75, 1.0), 0.2};
    }
}

// A random tree of the given depth: every operator, transforms on about half the nodes.
inline NodePtr randomTree(std::mt19937_64& rng, int depth) {
    NodePtr n;
    if (depth == 0) {
        n = leaf(randomPrimitive(rng, true));
    } else {
        NodePtr a = randomTree(rng, depth - 1), b = randomTree(rng, depth - 1);
        switch (std::uniform_int_distribution<int>(0, 2)(rng)) {
            case 0:
                n = unite(a, b);
                break;
            case 1:
                n = intersect(a, b);
                break;
            default:
                n = subtract(a, b);
                break;
        }
    }
    if (std::uniform_int_distribution<int>(0, 1)(rng)) n = transformed(randomAffine(rng), n);
    return n;
}

}  // namespace csg::testing
