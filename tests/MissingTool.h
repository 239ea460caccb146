// A test that needs a tool the install script brings (openscad, the Khronos glTF validator,
// xdotool, an X server) skips where the tool is missing on a developer's machine; in CI
// (CI=true) the same absence fails the test, since the install script was meant to bring the
// tool there and a skip would silently remove the check.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace csg::testing {

inline bool inCi() {
    const char* ci = std::getenv("CI");
    return ci != nullptr && std::strcmp(ci, "true") == 0;
}

// Whether Debian's openscad runs here: the oracle of the tests that compare with OpenSCAD 2021.
inline bool haveOpenScad() {
    return std::system("openscad --version >/dev/null 2>&1") == 0;
}

}  // namespace csg::testing

// In a test body (or SetUp): skip with `why`, or fail with it under CI=true.
#define SKIP_OR_FAIL_IN_CI(why)                                                        \
    do {                                                                               \
        if (::csg::testing::inCi()) FAIL() << "in CI a missing tool fails: " << (why); \
        GTEST_SKIP() << (why);                                                         \
    } while (0)
