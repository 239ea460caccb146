// Replays every file of the given directories through a fuzz target's body without libFuzzer,
// so the normal build keeps the corpora (and each crash they record) fixed: `part` is the part
// language's (FuzzInput.h), `mesh` the mesh readers' (FuzzMeshInput.h).
// Usage: fuzz_replay part|mesh DIR...; exit 0 when every input ran, 2 on bad usage.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "tests/fuzz/FuzzInput.h"
#include "tests/fuzz/FuzzMeshInput.h"

int main(int argc, char** argv) {
    const std::string_view target = argc > 1 ? argv[1] : "";
    if (argc < 3 || (target != "part" && target != "mesh")) {
        std::fprintf(stderr, "usage: fuzz_replay part|mesh DIR...\n");
        return 2;
    }
    std::vector<std::filesystem::path> files;
    for (int i = 2; i < argc; ++i) {
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(argv[i], ec))
            if (entry.is_regular_file()) files.push_back(entry.path());
        if (ec) {
            std::fprintf(stderr, "fuzz_replay: cannot list %s: %s\n", argv[i],
                         ec.message().c_str());
            return 2;
        }
    }
    // A replay of nothing would pass whatever the code does: a corpus that went missing (a
    // moved folder, a CMake path) must fail the test, not silently shrink it to zero inputs.
    if (files.empty()) {
        std::fprintf(stderr, "fuzz_replay: no inputs found in the corpus folders given\n");
        return 1;
    }
    std::sort(files.begin(), files.end());
    const auto start = std::chrono::steady_clock::now();
    for (const auto& file : files) {
        std::ifstream in(file, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        std::fprintf(stderr, "%s\n", file.filename().c_str());  // names the input if it crashes
        if (target == "part")
            fuzz::evaluateInput(text.str());
        else
            fuzz::readMeshInput(text.str());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("fuzz_replay: %zu inputs in %.2f s\n", files.size(), seconds);
    return 0;
}
