// Writes a file so that readers only ever see the old file or the complete new one: the bytes
// go to a temporary file in the same directory (so rename stays on one file system), which is
// renamed over the target by commit(). If commit() is never reached (an error, an exception,
// an early return) the destructor removes the temporary file: no partial output is left.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace csg {

class AtomicFile {
public:
    // Creates the temporary file. On failure ok() is false and error() says why.
    explicit AtomicFile(std::filesystem::path target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    bool ok() const { return file_ != nullptr; }
    const std::string& error() const { return error_; }
    // The open temporary file, for writers that take a FILE* (libpng). nullptr unless ok().
    std::FILE* stream() const { return file_; }

    // Flushes, syncs and closes the temporary file, then renames it to the target. Returns
    // false (with error()) if any step fails, in which case the temporary file is removed.
    bool commit();
    // Marks the write as failed with a reason; the destructor then removes the temporary file.
    void fail(std::string reason);

private:
    void discard();

    std::filesystem::path target_;
    std::filesystem::path temp_;
    std::FILE* file_ = nullptr;
    std::string error_;
};

// Writes bytes to target through an AtomicFile. Returns "" on success, else why it failed
// (the target is then left as it was).
std::string writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

}  // namespace csg
