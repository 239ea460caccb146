// One exactly rounded a * b + c for the per-ray path, by the FMA instruction where the CPU has it.
#pragma once

#include <cmath>

namespace csg {

// Why not plain std::fma: a default x86-64 build (no -mfma, so no __FMA__) may not assume the
// instruction, so every std::fma is a call into libm, around which the ray loop spills every
// live register. Where the CPU has FMA (checked once, at start-up) the instruction is used
// directly. Both paths round a * b + c once, exactly, so the bits are the same either way; a
// call made before the check has run (static initialization) just takes the libm path.
// Builds that may assume FMA (__FMA__) and other targets keep std::fma, which the compiler
// turns into the instruction where there is one.
#if defined(__x86_64__) && !defined(__FMA__)
inline const bool kCpuHasFma = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("fma") != 0;
}();

inline double fusedMultiplyAdd(double a, double b, double c) {
    if (!kCpuHasFma) return std::fma(a, b, c);
    asm("vfmadd231sd %[b], %[a], %[c]" : [c] "+x"(c) : [a] "x"(a), [b] "x"(b));
    return c;
}
#else
inline double fusedMultiplyAdd(double a, double b, double c) {
    return std::fma(a, b, c);
}
#endif

}  // namespace csg
