// The files of one evaluation: their names (for diagnostics), their text (kept alive while the
// AST refers to locations in them) and how include/use names resolve.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace io {

class SourceFiles {
public:
    // Adds text under a display name; returns its file index.
    uint32_t add(std::string name, std::filesystem::path path, std::string text);
    // Reads a file from disk; nothing (and a message in error) when it cannot be read or
    // files are not allowed.
    std::optional<uint32_t> load(const std::filesystem::path& path, std::string& error);

    // false: load() refuses every file (evaluating untrusted text).
    void allowFiles(bool allowed) { filesAllowed_ = allowed; }

    const std::string& name(uint32_t file) const { return files_[file].name; }
    const std::string& text(uint32_t file) const { return files_[file].text; }
    const std::filesystem::path& path(uint32_t file) const { return files_[file].path; }
    size_t size() const { return files_.size(); }
    // Frees a file's text once it is parsed (names stay for diagnostics).
    void releaseText(uint32_t file) { std::string().swap(files_[file].text); }

    // A name written in include <name> / use <name> inside file `from`, found as OpenSCAD
    // finds it: absolute names as they are; otherwise the first that exists of that file's
    // directory, each directory of $OPENSCADPATH (':'-separated, in order), the user library
    // (~/.local/share/OpenSCAD/libraries) and the system one (/usr/share/openscad/libraries).
    // When none has it, the path next to `from` (so the error names where it was expected).
    std::filesystem::path resolve(const std::string& written, uint32_t from) const;

private:
    struct File {
        std::string name;
        std::filesystem::path path;
        std::string text;
    };
    std::vector<File> files_;
    bool filesAllowed_ = true;
};

}  // namespace io
