// The closed set of primitives. Registering a new one is one line in this variant (plus its
// own files and tests: see the recipe in primitives/Primitive.h); csg/ dispatches over it with
// std::visit, which compiles to a jump table rather than a virtual call. Everything outside
// primitives/ that needs a primitive's name, description, ball or kind asks the functions
// below, which are derived from the variant.
#pragma once

#include <array>
#include <optional>
#include <variant>

#include "primitives/AlgebraicSurface.h"
#include "primitives/Box.h"
#include "primitives/ConvexPolytope.h"
#include "primitives/Cylinder.h"
#include "primitives/Extrusion.h"
#include "primitives/HalfSpace.h"
#include "primitives/PatchSet.h"
#include "primitives/Polyhedron.h"
#include "primitives/Sphere.h"
#include "primitives/Torus.h"

namespace csg {

using Primitive = std::variant<Sphere, Box, Cylinder, HalfSpace, Torus, AlgebraicSurface, PatchSet,
                               Polyhedron, ConvexPolytope, Extrusion>;

namespace detail {
template <class Variant>
struct PrimitiveTable;
template <class... Shapes>
struct PrimitiveTable<std::variant<Shapes...>> {
    static_assert((PrimitiveShape<Shapes> && ...), "every primitive meets the contract");
    static constexpr std::array<const char*, sizeof...(Shapes)> names{Shapes::kName...};
};
}  // namespace detail

// The language's name of every primitive, in the variant's order.
inline constexpr auto kPrimitiveNames = detail::PrimitiveTable<Primitive>::names;

// The language's name of p's kind ("cube", "sphere", ...).
inline const char* primitiveName(const Primitive& p) {
    return kPrimitiveNames[p.index()];
}

// p's parameters as members of the JSON object being written.
inline void describePrimitive(JsonWriter& json, const Primitive& p) {
    std::visit([&](const auto& shape) { shape.describe(json); }, p);
}

// True for a sheet: an open surface with no inside (see HasSheet in Primitive.h).
inline bool isSheet(const Primitive& p) {
    return std::visit(
        [](const auto& shape) {
            if constexpr (HasSheet<std::decay_t<decltype(shape)>>)
                return shape.isSheet();
            else
                return false;
        },
        p);
}

// True when p is convex (see HasConvexSolid in Primitive.h).
inline bool isConvex(const Primitive& p) {
    return std::visit(
        [](const auto& shape) { return HasConvexSolid<std::decay_t<decltype(shape)>>; }, p);
}

// True when p's whole surface is one plane (see HasPlanarSurface in Primitive.h).
inline bool isPlanar(const Primitive& p) {
    return std::visit(
        [](const auto& shape) { return HasPlanarSurface<std::decay_t<decltype(shape)>>; }, p);
}

// p's outward unit normal at `local`, a point of its surface in its own frame, on `face`.
inline Vec3 primitiveNormal(const Primitive& p, const Vec3& local, uint16_t face) {
    return std::visit([&](const auto& shape) { return shape.normal(local, face); }, p);
}

// p's bounding ball in its own frame, for primitives that have one (see HasBoundingBall).
inline std::optional<LocalBall> boundingBall(const Primitive& p) {
    return std::visit(
        [](const auto& shape) -> std::optional<LocalBall> {
            if constexpr (HasBoundingBall<std::decay_t<decltype(shape)>>)
                return shape.boundingBall();
            else
                return std::nullopt;
        },
        p);
}

}  // namespace csg
