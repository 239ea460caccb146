// projection() and resize(): see io/MeasureModules.h.
#include "io/MeasureModules.h"

#include <cmath>
#include <stdexcept>

#include "csg/Scene.h"
#include "csg/section/Projection.h"
#include "io/BoundArgs.h"
#include "io/Shapes2D.h"

namespace io {

namespace {

// info's "accuracy" of a projection that meshed something (static texts: the leaf keeps a
// pointer).
constexpr const char* kMeshedLeaves =
    "approximate: curved leaves were made polyhedra within 5e-4 of their bounds' diagonal "
    "(inscribed, or csgray's mesher) before projecting";
constexpr const char* kMeshedSubtree =
    "approximate: an intersection or difference with too many faces to project exactly was "
    "meshed within 5e-4 of its bounds' diagonal";

// A failure of the measuring (an unbounded child, a transform compile refuses) as an error at
// the call.
template <class F>
auto measured(Evaluator& e, const InstantiationStmt& s, F&& f) {
    try {
        return f();
    } catch (const csg::CompileError& error) {
        e.fail(s.loc, s.name + "(): " + error.what());
    } catch (const std::invalid_argument& error) {
        e.fail(s.loc, s.name + "(): " + error.what());
    }
}

}  // namespace

Instance projectionModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                          const GeomState& state) {
    BoundArgs b =
        bindArgs(e, s, ctx, {"cut", "convexity"}, "projection(cut = false | true, convexity)");
    // OpenSCAD reads cut only when it is a boolean.
    bool cut = false;
    if (b.given(0)) {
        if (b[0].isBool())
            cut = b[0].asBool();
        else
            e.warn(b.loc(0), "projection(): cut = " + b[0].brief() +
                                 " is not true or false; the shadow is taken, as in OpenSCAD");
    }
    uint32_t tag = 0;
    Instance children = childrenGroup(e, b, ctx, state, &tag);
    if (!children || !*children) return children;
    if (dimensionOf(*children) != 3) {
        e.warn(s.loc,
               "projection(): its children are 2-D shapes, not solids; ignored, as in "
               "OpenSCAD");
        return csg::NodePtr();
    }
    const csg::Tags tags{e.sourceTag(s.loc, e.childPath(state, s.name)), state.material};
    // Extrusions standing along z: their own outlines, curves and all.
    if (!cut)
        if (std::optional<csg::NodePtr> exact = csg::axialShadow(*children, tags)) return *exact;
    const csg::ProjectionResult result = measured(
        e, s, [&] { return cut ? csg::sectionAtZ0(*children) : csg::shadowAlongZ(*children); });
    if (result.outline.segments.empty()) return csg::NodePtr();
    csg::Extrusion leaf =
        csg::Extrusion::plane(std::make_shared<csg::Outline>(result.outline), "projection");
    if (result.meshedSubtrees > 0)
        leaf.accuracy = kMeshedSubtree;
    else if (result.meshedLeaves > 0)
        leaf.accuracy = kMeshedLeaves;
    return csg::leaf(leaf, tags);
}

namespace {

// The bounds of a 2-D shape's outlines, bottom-up.
csg::Bounds2 shapeBounds(const csg::Node* node) {
    if (!node) return {};
    if (node->op == csg::Op::Leaf) return std::get<csg::Extrusion>(node->primitive).box;
    const csg::Bounds2 l = shapeBounds(node->left.get());
    const csg::Bounds2 r = shapeBounds(node->right.get());
    switch (node->op) {
        case csg::Op::Union: {
            csg::Bounds2 u = l;
            if (!r.empty()) u.add(r.lo), u.add(r.hi);
            return u;
        }
        case csg::Op::Intersection:
            return {glm::max(l.lo, r.lo), glm::min(l.hi, r.hi)};
        default:
            return l;
    }
}

}  // namespace

Instance resizeModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"newsize", "auto", "convexity"},
                           "resize(newsize = [x, y, z], auto = false | [x, y, z], convexity)");
    // As OpenSCAD 2021 reads them: newsize only as a vector (entries that are not numbers are
    // 0), auto as a boolean for all axes or a vector of booleans.
    csg::Vec3 newsize(0.0);
    if (b.given(0)) {
        if (b[0].isVector()) {
            const ValueList& l = b[0].list();
            for (size_t k = 0; k < std::min<size_t>(l.size(), 3); ++k)
                if (l[k].isNumber() && std::isfinite(l[k].number()))
                    newsize[int(k)] = l[k].number();
        } else {
            e.warn(b.loc(0), "resize(): newsize = " + b[0].brief() +
                                 " is not a vector [x, y, z]; nothing is resized, as in OpenSCAD");
        }
    }
    bool autosize[3] = {false, false, false};
    if (b.given(1)) {
        if (b[1].isBool()) {
            autosize[0] = autosize[1] = autosize[2] = b[1].asBool();
        } else if (b[1].isVector()) {
            const ValueList& l = b[1].list();
            for (size_t k = 0; k < std::min<size_t>(l.size(), 3); ++k) autosize[k] = l[k].asBool();
        }
    }
    Instance children = childrenGroup(e, b, ctx, state);
    if (!children || !*children) return children;
    const int dims = dimensionOf(*children);
    csg::Vec3 size(1.0);
    if (dims == 2) {
        const csg::Bounds2 box = shapeBounds(children->get());
        if (box.empty()) return csg::NodePtr();
        size = csg::Vec3(box.hi - box.lo, 0.0);
        newsize.z = 0.0;  // a 2-D shape has no z to resize
    } else {
        const csg::Bounds3 box = measured(e, s, [&] { return csg::solidBounds(*children); });
        if (box.empty()) return csg::NodePtr();
        size = box.hi - box.lo;
    }
    // OpenSCAD's factors (PolySet::resize, Polygon2d::resize).
    int largest = 0;
    for (int k = 1; k < 3; ++k)
        if (newsize[k] > newsize[largest]) largest = k;
    csg::Vec3 factor(1.0);
    for (int k = 0; k < 3; ++k) {
        if (!(newsize[k] > 0.0)) continue;
        if (!(size[k] > 0.0)) {
            e.warn(s.loc, "Resize in direction normal to flat object is not implemented");
            return children;
        }
        factor[k] = newsize[k] / size[k];
    }
    const double autoscale = factor[largest];
    for (int k = 0; k < 3; ++k)
        if (autosize[k] && !(newsize[k] > 0.0)) factor[k] = autoscale;
    if (dims == 2) factor.z = 1.0;
    const csg::Mat4 m = glm::scale(csg::Mat4(1.0), factor);
    return dims == 2 ? transformed2D(m, *children) : csg::transformed(m, *children);
}

}  // namespace io
