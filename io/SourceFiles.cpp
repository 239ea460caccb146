#include "io/SourceFiles.h"

#include <cstdlib>
#include <sstream>

#include "primitives/base/ReadFile.h"

namespace io {

uint32_t SourceFiles::add(std::string name, std::filesystem::path path, std::string text) {
    files_.push_back({std::move(name), std::move(path), std::move(text)});
    return static_cast<uint32_t>(files_.size() - 1);
}

std::optional<uint32_t> SourceFiles::load(const std::filesystem::path& path, std::string& error) {
    if (!filesAllowed_) {
        error = "reading files is not allowed here";
        return std::nullopt;
    }
    std::string text;
    switch (csg::readWholeFile(path, text)) {
        case csg::ReadFailure::None:
            return add(path.string(), path, std::move(text));
        case csg::ReadFailure::IsDirectory:
            error = "'" + path.string() + "' is a directory";
            return std::nullopt;
        case csg::ReadFailure::CannotOpen:
            error = "cannot open '" + path.string() + "'";
            return std::nullopt;
        case csg::ReadFailure::CannotRead:
            break;
    }
    error = "cannot read '" + path.string() + "'";
    return std::nullopt;
}

// The library directories searched after the including file's own, in OpenSCAD's order.
static std::vector<std::filesystem::path> libraryDirectories() {
    std::vector<std::filesystem::path> dirs;
    if (const char* env = std::getenv("OPENSCADPATH")) {
        const std::string list(env);
        for (size_t begin = 0; begin <= list.size();) {
            size_t end = list.find(':', begin);
            if (end == std::string::npos) end = list.size();
            if (end > begin) dirs.emplace_back(list.substr(begin, end - begin));
            begin = end + 1;
        }
    }
    if (const char* home = std::getenv("HOME"); home && *home)
        dirs.push_back(std::filesystem::path(home) / ".local/share/OpenSCAD/libraries");
    dirs.emplace_back("/usr/share/openscad/libraries");
    return dirs;
}

std::filesystem::path SourceFiles::resolve(const std::string& written, uint32_t from) const {
    const std::filesystem::path p(written);
    if (p.is_absolute()) return p;
    const std::filesystem::path local = files_[from].path.parent_path() / p;
    if (!filesAllowed_) return local;  // no looking around the disk either
    std::error_code ec;
    if (std::filesystem::exists(local, ec)) return local;
    for (const auto& dir : libraryDirectories()) {
        const std::filesystem::path candidate = dir / p;
        if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
    }
    return local;
}

}  // namespace io
