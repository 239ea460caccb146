// Error-free transformations: a + b and a * b as hi + lo exactly, the building blocks of the
// double-double arithmetic that polishes roots (Torus.cpp) and shifts polynomials
// (ExactPolynomial.cpp).
#pragma once

#include "primitives/base/Fma.h"

namespace csg {

struct Sum2 {
    double hi, lo;
};

// Knuth's twoSum: exact for any a, b (no ordering of magnitudes assumed) barring overflow.
inline Sum2 twoSum(double a, double b) {
    const double s = a + b;
    const double bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

// The product's low part by one fma (fusedMultiplyAdd: the instruction where the CPU has it).
inline Sum2 twoProduct(double a, double b) {
    const double p = a * b;
    return {p, fusedMultiplyAdd(a, b, -p)};
}

}  // namespace csg
