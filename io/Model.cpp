#include "io/Model.h"

namespace io {

const SourceInfo& Model::source(uint32_t tag) const {
    return tag < sources.size() ? sources[tag] : sources.front();
}

const std::string& Model::sourceFile(uint32_t tag) const {
    static const std::string unknown;
    const uint32_t file = source(tag).fileIndex;
    return tag != 0 && file < files.size() ? files[file] : unknown;
}

const std::string& Model::modulePath(uint32_t tag) const {
    static const std::string unknown;
    const uint32_t path = source(tag).modulePathIndex;
    return path < modulePaths.size() ? modulePaths[path] : unknown;
}

std::string Model::describeSource(uint32_t tag) const {
    const SourceInfo& s = source(tag);
    std::string out = sourceFile(tag);
    if (s.line > 0) out += ":" + std::to_string(s.line) + ":" + std::to_string(s.col);
    return out;
}

}  // namespace io
