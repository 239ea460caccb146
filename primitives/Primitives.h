// The closed set of primitives. Registering a new one is one line in this variant (plus its
// own file and tests); csg/ dispatches over it with std::visit, which compiles to a jump table
// rather than a virtual call.
#pragma once

#include <variant>

#include "primitives/AlgebraicSurface.h"
#include "primitives/Box.h"
#include "primitives/Cylinder.h"
#include "primitives/HalfSpace.h"
#include "primitives/PatchSet.h"
#include "primitives/Sphere.h"
#include "primitives/Torus.h"

namespace csg {

using Primitive =
    std::variant<Sphere, Box, Cylinder, HalfSpace, Torus, AlgebraicSurface, PatchSet>;

static_assert(PrimitiveShape<Sphere> && PrimitiveShape<Box> && PrimitiveShape<Cylinder> &&
              PrimitiveShape<HalfSpace> && PrimitiveShape<Torus> &&
              PrimitiveShape<AlgebraicSurface> && PrimitiveShape<PatchSet>);

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

}  // namespace csg
