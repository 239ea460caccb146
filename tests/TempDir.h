// Test support: a fresh directory under the system's temporary one for a test's files.
// Not for product code.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace csg::testing {

// Named name_PID, emptied first (a crashed run with the same pid may have left one) and removed
// with its files when the test ends (also when an ASSERT returns early).
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& name)
        : path(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(getpid()))) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
};

}  // namespace csg::testing
