// The algebraic-surface class both solver benchmarks share: the product of degree / 2
// origin-centred spheres with radii^2 from 0.25 to 1.4, whose ray polynomials have degree
// `degree` and real roots known in closed form.
#pragma once

#include "primitives/AlgebraicSurface.h"

namespace csg {

inline AlgebraicSurface shellSurface(int degree) {
    const ExactPolynomial x = ExactPolynomial::x(), y = ExactPolynomial::y(),
                          z = ExactPolynomial::z();
    const ExactPolynomial r2 = *x.times(x) + *y.times(y) + *z.times(z);
    ExactPolynomial f = ExactPolynomial::constant(1.0);
    for (int i = 0; i < degree / 2; ++i)
        f = *f.times(r2 - ExactPolynomial::constant(0.25 + 1.15 * i / (degree / 2)));
    return AlgebraicSurface::make(f, {Vec3(-1.5), Vec3(1.5)});
}

}  // namespace csg
