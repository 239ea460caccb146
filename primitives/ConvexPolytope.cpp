// Notation: t is the parameter of the line o + t d. For plane i, gap = c_i - n_i . o is how far
// o lies inside it (negative: outside) and nd = n_i . d how fast the line leaves it; the line
// crosses it at t = gap / nd, entering where nd < 0 and leaving where nd > 0.
#include "primitives/ConvexPolytope.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace csg {

namespace {

// The area vector of a face (twice its area times its normal), from the fan of triangles at its
// first vertex, in coordinates divided by `scale` so that neither tiny nor huge solids underflow
// or overflow in the cross products. Exact in direction for a planar face up to rounding; for a
// face whose vertices were rounded off its plane it is the least-squares-like average of its
// triangles' normals.
Vec3 areaVector(const std::vector<Vec3>& vertices, std::span<const uint32_t> face, double scale) {
    const Vec3 first = vertices[face[0]] / scale;
    Vec3 sum(0.0);
    for (size_t k = 1; k + 1 < face.size(); ++k) {
        const Vec3 a = vertices[face[k]] / scale - first;
        const Vec3 b = vertices[face[k + 1]] / scale - first;
        sum += glm::cross(a, b);
    }
    return sum;
}

ConvexPolytope invalid(std::shared_ptr<ConvexPolytopeData> data, const char* why) {
    data->invalid = why;
    data->planes.clear();
    return ConvexPolytope{std::move(data)};
}

}  // namespace

ConvexPolytope ConvexPolytope::fromFaces(std::vector<Vec3> vertices,
                                         std::span<const uint32_t> faceVertices,
                                         std::span<const uint32_t> faceStarts, Origin origin) {
    auto data = std::make_shared<ConvexPolytopeData>();
    data->origin = origin;
    data->faceVertices.assign(faceVertices.begin(), faceVertices.end());
    data->faceStarts.assign(faceStarts.begin(), faceStarts.end());
    const size_t faceCount = faceStarts.empty() ? 0 : faceStarts.size() - 1;
    if (faceCount > kMaxPlanes)
        return invalid(std::move(data), "a convex polyhedron may have at most 65535 faces");
    if (faceCount < 4 || vertices.size() < 4)
        return invalid(std::move(data), "a convex polyhedron needs at least 4 faces");
    for (const Vec3& v : vertices) {
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            return invalid(std::move(data), "a convex polyhedron's vertices must be finite");
        data->box.extend(v);
    }

    // Step 1: the centroid of the vertices, strictly inside a convex solid with volume, tells
    // each face which way is out whatever its winding.
    Vec3 centroid(0.0);
    for (const Vec3& v : vertices) centroid += v;
    centroid /= double(vertices.size());
    double scale = 0.0;
    for (const Vec3& v : vertices)
        scale = std::max({scale, std::abs(v.x), std::abs(v.y), std::abs(v.z)});

    // Step 2: one plane per face, through the face's vertices.
    data->planes.reserve(faceCount);
    for (size_t f = 0; f < faceCount; ++f) {
        const uint32_t begin = faceStarts[f], end = faceStarts[f + 1];
        if (end < begin + 3 || end > faceVertices.size())
            return invalid(std::move(data), "a convex polyhedron's face has fewer than 3 vertices");
        const std::span<const uint32_t> face = faceVertices.subspan(begin, end - begin);
        for (uint32_t index : face)
            if (index >= vertices.size())
                return invalid(std::move(data), "a convex polyhedron's face names no vertex");
        const Vec3 area = areaVector(vertices, face, scale);
        const double length = glm::length(area);
        if (!(length > 0.0) || !std::isfinite(length))
            return invalid(std::move(data), "a convex polyhedron's face has no area");
        PolytopePlane plane{area / length, -kInfinity};
        // Outward: the vertices' centroid lies below the plane.
        if (glm::dot(plane.normal, vertices[face[0]] - centroid) < 0.0)
            plane.normal = -plane.normal;
        // Pushed out to the face vertex farthest along the normal: the face's rounded vertices
        // do not lie exactly on one plane, and none of them may fall outside the solid.
        for (uint32_t index : face)
            plane.offset = std::max(plane.offset, glm::dot(plane.normal, vertices[index]));
        data->planes.push_back(plane);
    }

    // Step 3: a bounding ball where it is tighter than the box.
    const double boxVolume = data->box.extent().x * data->box.extent().y * data->box.extent().z;
    for (const Vec3& center : {Vec3(0.0), data->box.center()}) {
        double radius2 = 0.0;
        for (const Vec3& v : vertices)
            radius2 = std::max(radius2, glm::dot(v - center, v - center));
        const double radius = std::sqrt(radius2);
        if (radius < data->ball.radius) data->ball = {center, radius};
    }
    const double ballVolume = 4.0 / 3.0 * std::numbers::pi * std::pow(data->ball.radius, 3);
    if (!(ballVolume < boxVolume)) data->ball.radius = kInfinity;

    // Step 4: the planes again, four to a block for spans(); the last block is filled with
    // planes no line can cross (n = 0, offset 1: parallel, and inside by 1).
    data->planeBlocks.resize((faceCount + kPlaneLanes - 1) / kPlaneLanes);
    for (PlaneBlock& block : data->planeBlocks) block.offset = PlaneLanes{} + 1.0;
    for (size_t f = 0; f < faceCount; ++f) {
        PlaneBlock& block = data->planeBlocks[f / kPlaneLanes];
        const PolytopePlane& plane = data->planes[f];
        block.nx[f % kPlaneLanes] = plane.normal.x;
        block.ny[f % kPlaneLanes] = plane.normal.y;
        block.nz[f % kPlaneLanes] = plane.normal.z;
        block.offset[f % kPlaneLanes] = plane.offset;
    }

    data->vertices = std::move(vertices);
    return ConvexPolytope{std::move(data)};
}

const char* ConvexPolytope::invalidReason() const {
    if (!data) return "an empty convex polyhedron";
    return data->invalid;
}

Bounds3 ConvexPolytope::bounds() const {
    return data->box;
}

Bounds3 ConvexPolytope::boundsUnder(const Mat4& m) const {
    Bounds3 box;
    for (const Vec3& v : data->vertices) box.extend(transformPoint(m, v));
    return box;
}

void ConvexPolytope::spans(const Vec3& o, const Vec3& d, LocalSpans& out) const {
    double tIn = -kInfinity, tOut = kInfinity;
    uint16_t faceIn = kClipFace, faceOut = kClipFace;
    // The caller reads the span only within [from, to] (LocalSpans): once its entry lies past
    // to + margin, or its exit before from - margin, it shows nothing there, and the planes left
    // need not be tested (a line met far beyond the best hit so far, or a classifying line a
    // few eps long that passes the polytope by). Past `to` is a span left out (cutAtTo).
    const double enterBy = out.to + out.margin, leaveFrom = out.from - out.margin;
    const PlaneLanes dx = PlaneLanes{} + d.x, dy = PlaneLanes{} + d.y, dz = PlaneLanes{} + d.z;
    const PlaneLanes ox = PlaneLanes{} + o.x, oy = PlaneLanes{} + o.y, oz = PlaneLanes{} + o.z;
    const std::vector<PlaneBlock>& blocks = data->planeBlocks;
    for (size_t b = 0; b < blocks.size(); ++b) {
        const PlaneBlock& block = blocks[b];
        // In the operation order of glm::dot, so each lane has the bits of the scalar form.
        const PlaneLanes nd = (block.nx * dx + block.ny * dy) + block.nz * dz;
        const PlaneLanes gap = block.offset - ((block.nx * ox + block.ny * oy) + block.nz * oz);
        // The crossing t = gap / nd matters only where it may move an end: t > tIn is
        // gap < tIn nd for nd < 0, t < tOut is gap < tOut nd for nd > 0, a multiplication for
        // every plane and a division only for the few that pass (the two forms differ only
        // where t is within rounding of the end, which then moves by an ulp or not). A line
        // parallel to a plane (nd = 0) and outside it (gap < 0) misses.
        const PlaneMask moves = ((nd < 0.0) & (gap < tIn * nd)) | ((nd > 0.0) & (gap < tOut * nd)) |
                                ((nd == 0.0) & (gap < 0.0));
        if (!(moves[0] | moves[1] | moves[2] | moves[3])) continue;
        for (size_t lane = 0; lane < kPlaneLanes; ++lane) {
            if (!moves[lane]) continue;
            const auto face = uint16_t(b * kPlaneLanes + lane);
            // A crossing that overflows (nd tiny) is at -inf or +inf, which is right: the line
            // is then as good as parallel, entering never (gap > 0) or only beyond every exit.
            if (nd[lane] < 0.0) {
                const double t = gap[lane] / nd[lane];
                if (t > tIn) tIn = t, faceIn = face;
            } else if (nd[lane] > 0.0) {
                const double t = gap[lane] / nd[lane];
                if (t < tOut) tOut = t, faceOut = face;
            } else {
                return;  // parallel to the plane and outside it
            }
        }
        if (tIn > tOut) return;  // the ends have crossed: no later plane brings them back
        if (tOut < leaveFrom) return;
        if (tIn > enterBy) {
            out.cutAtTo = true;
            return;
        }
    }
    // Misses, or a direction too small to leave the solid in a finite t (d = 0).
    if (!(tIn <= tOut) || !std::isfinite(tIn) || !std::isfinite(tOut)) return;
    out.add(tIn, faceIn, tOut, faceOut);
}

bool ConvexPolytope::inside(const Vec3& p) const {
    for (const PolytopePlane& plane : data->planes)
        if (glm::dot(plane.normal, p) > plane.offset) return false;
    return true;
}

Vec3 ConvexPolytope::normal(const Vec3&, uint16_t face) const {
    return face < data->planes.size() ? data->planes[face].normal : Vec3(0.0, 0.0, 1.0);
}

void ConvexPolytope::describe(JsonWriter& json) const {
    if (!data) return;
    if (data->origin.module) {
        json.key("faceted").value(data->origin.module);
        json.key("fragments").value(data->origin.fragments);
        if (data->origin.rings > 0) json.key("rings").value(data->origin.rings);
    }
    json.key("planes").value(uint64_t(data->planes.size()));
    json.key("vertices").value(uint64_t(data->vertices.size()));
}

LocalBall ConvexPolytope::boundingBall() const {
    return data->ball;
}

size_t ConvexPolytope::planeCount() const {
    return data ? data->planes.size() : 0;
}

}  // namespace csg
