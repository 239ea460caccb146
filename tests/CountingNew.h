// A global operator new that counts, for the tests that prove a query allocates nothing.
// Include it in exactly one file of a test program: it replaces the program's operator new.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace csg::testing {
// Calls of operator new so far; compare before and after the code under watch.
inline std::atomic<long> allocations{0};
}  // namespace csg::testing

void* operator new(std::size_t size) {
    ++csg::testing::allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
// The replaced operator new above takes its memory from malloc, so free is its match; GCC,
// seeing a new-expression's pointer reach free() once both are inlined, warns otherwise.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
#pragma GCC diagnostic pop
