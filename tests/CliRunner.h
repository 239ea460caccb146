// Runs the built csgray binary for end-to-end tests: argument quoting, captured stdout and
// stderr, exit status, a scratch directory per test, and the probe output parsed as spans.
// CSGRAY_EXE and CSGRAY_SAMPLES come from tests/CMakeLists.txt.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "TextFiles.h"

namespace cli {

namespace fs = std::filesystem;

struct RunResult {
    int exitCode = -1;
    std::string out;  // stdout
    std::string err;  // stderr
};

using csg::testing::readFile;
using csg::testing::shellQuote;
using csg::testing::writeFile;

inline fs::path samplePath(const std::string& name) {
    return fs::path(CSGRAY_SAMPLES) / name;
}

// A fresh directory for one test, removed when the test ends.
class ScratchDir {
public:
    ScratchDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = "csgray_cli_" + std::to_string(::getpid()) + "_" +
                           info->test_suite_name() + "_" + info->name();
        for (char& c : name)
            if (c == '/') c = '_';  // parameterized tests have a '/' in their names
        path_ = fs::temp_directory_path() / name;
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }
    fs::path operator/(const std::string& name) const { return path_ / name; }

private:
    fs::path path_;
};

// Runs csgray with args (and stdin from a file when given); stdout and stderr are captured
// through files in dir.
inline RunResult runCsgray(const std::vector<std::string>& args, const fs::path& dir,
                           const std::string& stdinFile = "") {
    std::string command = shellQuote(CSGRAY_EXE);
    for (const std::string& a : args) command += " " + shellQuote(a);
    const fs::path out = dir / ".stdout", err = dir / ".stderr";
    command += " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string());
    command += " <" + shellQuote(stdinFile.empty() ? "/dev/null" : stdinFile);
    const int status = std::system(command.c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readFile(out);
    r.err = readFile(err);
    fs::remove(out);
    fs::remove(err);
    return r;
}

// One span of a probe: the t of its ends (a distance, since the direction is unit length).
struct SpanT {
    double in, out;
};

inline std::vector<SpanT> spansOf(const nlohmann::json& ray) {
    std::vector<SpanT> spans;
    for (const auto& s : ray.at("spans"))
        spans.push_back({s.at("in").at("t").get<double>(), s.at("out").at("t").get<double>()});
    return spans;
}

inline std::string describe(const std::vector<SpanT>& spans) {
    std::ostringstream s;
    s.precision(12);
    s << "{";
    for (const SpanT& sp : spans) s << " [" << sp.in << ", " << sp.out << "]";
    return s.str() + " }";
}

inline bool sameSpans(const std::vector<SpanT>& a, const std::vector<SpanT>& b, double tol) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::abs(a[i].in - b[i].in) > tol || std::abs(a[i].out - b[i].out) > tol) return false;
    return true;
}

inline std::string vec3Arg(const std::array<double, 3>& v) {
    std::ostringstream s;
    s.precision(17);
    s << v[0] << "," << v[1] << "," << v[2];
    return s.str();
}

}  // namespace cli
