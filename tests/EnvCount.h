// Sample counts of the long property tests, overridable from the environment: a quick run
// while working on one piece, or a larger sweep.
#pragma once

#include <cstdlib>

namespace csg::testing {
// The positive integer in environment variable `name`; `fallback` when it is unset, not a
// number or not positive.
inline int countFromEnv(const char* name, int fallback) {
    const char* env = std::getenv(name);
    return env && std::atoi(env) > 0 ? std::atoi(env) : fallback;
}
}  // namespace csg::testing
