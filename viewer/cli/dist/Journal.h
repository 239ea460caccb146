// The journal of a long job (--resume): the results of its finished tasks (a tile's pixels, a
// frame's name), appended and flushed to the kernel as each arrives, in a file next to the
// output. A job killed at any point leaves a journal whose complete records are all valid (a
// torn last record is dropped when it is read back); a restarted job with the same key reads
// them and does only the rest. The job removes its journal once the output is committed.
//
// File: the line "csgray-journal 1 KEY\n", then records of u64 id, u64 size, the bytes and a
// u64 FNV-1a hash of id and bytes (native byte order: a journal is resumed where it was made).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace viewer::dist {

class Journal {
public:
    Journal() = default;
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    // Opens path for the job named key (a hash of everything that decides the output). A
    // journal of the same key is read back, each record given to found(id, bytes); one of
    // another key, or none, is started afresh (replaced != nullptr is then set when an old
    // one was there). Returns "" or why the journal cannot be used.
    std::string open(const std::filesystem::path& path, std::string_view key,
                     const std::function<void(uint64_t id, std::string_view bytes)>& found,
                     bool* replaced = nullptr);
    bool isOpen() const { return file_ != nullptr; }
    // The file opened (or last tried).
    const std::filesystem::path& path() const { return path_; }
    // Appends one record and flushes it to the kernel (it then survives the process being
    // killed); returns "" or why it could not.
    std::string append(uint64_t id, std::string_view bytes);
    // Closes and deletes the journal: the job it describes is complete.
    void remove();

private:
    std::filesystem::path path_;
    std::FILE* file_ = nullptr;
};

// The journal beside output: OUTPUT.journal.
std::filesystem::path journalPathFor(const std::filesystem::path& output);

// FNV-1a, 64 bits: the journal's record check and the job keys.
uint64_t fnv1a(std::string_view bytes, uint64_t hash = 0xcbf29ce484222325ull);

}  // namespace viewer::dist
