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

std::string Model::modulePath(uint32_t tag) const {
    return modulePathText(source(tag).modulePathIndex);
}

std::string Model::modulePathText(uint32_t path) const {
    if (path >= modulePaths.size()) return {};
    // Step 1: the steps from the top down (a path's parent always has a smaller index).
    std::vector<uint32_t> steps;
    for (uint32_t p = path; p != 0; p = modulePaths[p].parent) steps.push_back(p);
    // Step 2: their names joined.
    std::string text;
    for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
        if (!text.empty()) text += " > ";
        text += modulePaths[*it].name;
    }
    return text;
}

std::string Model::describeSource(uint32_t tag) const {
    const SourceInfo& s = source(tag);
    std::string out = sourceFile(tag);
    if (s.line > 0) out += ":" + std::to_string(s.line) + ":" + std::to_string(s.col);
    return out;
}

}  // namespace io
