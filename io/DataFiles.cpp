#include "io/DataFiles.h"

#include <algorithm>
#include <cctype>

namespace io {

std::filesystem::path lookupDataFile(Evaluator& e, Loc call, Loc at, const std::string& written) {
    std::filesystem::path path(written);
    if (!path.is_relative()) return path;
    const std::filesystem::path local = e.filePath(call.file).parent_path() / path;
    const std::filesystem::path top = e.filePath(0).parent_path() / path;
    std::error_code ec;
    if (!std::filesystem::exists(local, ec) && call.file != 0 && std::filesystem::exists(top, ec)) {
        e.warn(at, "Imported file (" + written +
                       ") found in document root instead of relative to the importing module. "
                       "This behavior is deprecated");
        return top;
    }
    return local;
}

std::string lowerExtension(std::string_view name) {
    std::string ext = std::filesystem::path(name).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace io
