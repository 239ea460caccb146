#include "viewer/cli/JobKey.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "viewer/cli/dist/Journal.h"

namespace viewer {

std::string jobKey(std::string_view command, const CommonOptions& common,
                   std::string_view settings) {
    std::string text = std::string(command) + "\n" + common.part + "\n";
    for (const auto& [name, value] : common.defines) text += "-D" + name + "=" + value + "\n";
    text +=
        std::to_string(int(common.curves)) + " " + std::to_string(int(common.polygonMethod)) + "\n";
    text += settings;
    text += "\n";
    std::error_code ignored;  // (no /proc: the build is simply not part of the key)
    const std::filesystem::path self("/proc/self/exe");
    text +=
        std::to_string(std::filesystem::file_size(self, ignored)) + " " +
        std::to_string(std::filesystem::last_write_time(self, ignored).time_since_epoch().count()) +
        "\n";
    std::ifstream part(common.part, std::ios::binary);
    text.append(std::istreambuf_iterator<char>(part), std::istreambuf_iterator<char>());
    char digits[17];
    std::snprintf(digits, sizeof digits, "%016llx", (unsigned long long)dist::fnv1a(text));
    return digits;
}

}  // namespace viewer
