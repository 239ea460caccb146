// offset(): OpenSCAD 2021's arguments (src/offset.cc OffsetModule::instantiate): no argument
// is r = 1; r, when it is a number, wins over delta; r gives round joins, delta miter joins,
// delta with chamfer = true square joins. The offset is exact unless the curve mode facets a
// circle of radius |r| with the call's $fn, $fa, $fs (--curves openscad, or $fn > 0 in auto):
// then it is OpenSCAD's own Clipper offset, with its arc tolerance
// |r| (1 - cos(180 deg / fragments(|r|))) (GeometryEvaluator::visit(OffsetNode)).
#include <cmath>
#include <memory>

#include "csg/derived/Clipper2D.h"
#include "csg/derived/Offset2D.h"
#include "io/BoundArgs.h"
#include "io/Degrees.h"
#include "io/DerivedModules.h"
#include "io/FacetedPrimitives.h"
#include "io/Shapes2D.h"

namespace io {

namespace {

csg::NodePtr offsetLeaf(csg::Outline outline, csg::Tags tags) {
    if (outline.segments.empty()) return csg::NodePtr();
    return csg::leaf(
        csg::Extrusion::plane(std::make_shared<csg::Outline>(std::move(outline)), "offset"), tags);
}

}  // namespace

Instance offsetModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state) {
    BoundArgs b = bindArgs(e, s, ctx, {"r", "delta", "chamfer"},
                           "offset(r) or offset(delta, chamfer = false)");
    // OpenSCAD reads $fn, $fa and $fs for offset() without clamping them.
    const FragmentSettings settings = unclampedFragmentSettings(e, b, ctx);
    double distance = 1.0;
    csg::OffsetJoin join = csg::OffsetJoin::Round;
    size_t given = 0;  // the argument the distance came from, for messages
    if (b.given(0) && b[0].isNumber()) {
        distance = b[0].number();
    } else if (b.given(1) && b[1].isNumber()) {
        distance = b[1].number();
        given = 1;
        join = b.given(2) && b[2].isBool() && b[2].asBool() ? csg::OffsetJoin::Chamfer
                                                            : csg::OffsetJoin::Miter;
    }
    const csg::Tags tags{e.sourceTag(s.loc, e.childPath(state, s.name)), state.material};
    Instance children = childrenGroup(e, b, ctx, state);
    if (!children || !*children) return children;
    if (dimensionOf(*children) != 2) {
        e.warn(s.loc, "offset(): its children are 3-D, not 2-D shapes; ignored, as in OpenSCAD");
        return csg::NodePtr();
    }
    if (!std::isfinite(distance)) {
        e.warn(b.given(given) ? b.loc(given) : s.loc, "offset(): the distance " +
                                                          formatNumber(distance) +
                                                          " is not finite; the result is empty");
        return csg::NodePtr();
    }
    if (distance == 0.0) return children;  // Clipper copies the polygons as they are

    if (isFaceted(e.curveMode(), settings)) {
        csg::ClipperOffsetSpec spec;
        spec.delta = distance;
        spec.join = join;
        const int64_t n = fragments(std::abs(distance), settings);
        spec.arcTolerance = std::abs(distance) * (1.0 - openscadCosDegrees(180.0 / double(n)));
        std::string error;
        std::optional<csg::Outline> outline = csg::clipperOffset(**children, spec, error);
        if (!outline) {
            e.warn(s.loc, "offset(): " + error + "; the result is empty");
            return csg::NodePtr();
        }
        e.spend(s.loc, outline->segments.size());
        return offsetLeaf(std::move(*outline), tags);
    }

    return exactOffset(e, s.loc, *children, distance, join, tags);
}

csg::NodePtr exactOffset(Evaluator& e, Loc loc, const csg::NodePtr& shape, double distance,
                         csg::OffsetJoin join, const csg::Tags& tags) {
    const csg::Region2D region(*shape);
    const csg::Boundary2D boundary = csg::boundaryOf(region);
    std::vector<csg::NodePtr> band;
    for (csg::Outline& chunk : csg::offsetBand(boundary, distance, join)) {
        e.spend(loc, chunk.segments.size());
        band.push_back(offsetLeaf(std::move(chunk), tags));
    }
    if (band.empty()) return shape;
    const csg::NodePtr bandNode = csg::uniteAll(band, tags);
    return distance > 0.0 ? csg::unite(shape, bandNode, tags)
                          : csg::subtract(shape, bandNode, tags);
}

}  // namespace io
