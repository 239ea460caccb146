#include "viewer/cli/dist/Journal.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace viewer::dist {

namespace {

std::string headerFor(std::string_view key) {
    return "csgray-journal 1 " + std::string(key) + "\n";
}

uint64_t recordHash(uint64_t id, std::string_view bytes) {
    return fnv1a(bytes, fnv1a(std::string_view(reinterpret_cast<const char*>(&id), sizeof id)));
}

// Reads the records after the header; returns the length of the part made of whole, valid
// records (a torn or damaged tail is cut off there).
size_t readRecords(const std::string& text, size_t at,
                   const std::function<void(uint64_t, std::string_view)>& found) {
    for (;;) {
        uint64_t id = 0, size = 0, hash = 0;
        if (text.size() - at < 2 * sizeof(uint64_t)) return at;
        std::memcpy(&id, text.data() + at, sizeof id);
        std::memcpy(&size, text.data() + at + 8, sizeof size);
        if (size > text.size() - at - 16 || text.size() - at - 16 - size < sizeof hash) return at;
        const std::string_view bytes(text.data() + at + 16, size);
        std::memcpy(&hash, text.data() + at + 16 + size, sizeof hash);
        if (hash != recordHash(id, bytes)) return at;
        found(id, bytes);
        at += 16 + size + sizeof hash;
    }
}

}  // namespace

uint64_t fnv1a(std::string_view bytes, uint64_t hash) {
    for (const char c : bytes) hash = (hash ^ uint8_t(c)) * 0x100000001b3ull;
    return hash;
}

std::filesystem::path journalPathFor(const std::filesystem::path& output) {
    return std::filesystem::path(output.string() + ".journal");
}

Journal::~Journal() {
    if (file_) std::fclose(file_);
}

std::string Journal::open(const std::filesystem::path& path, std::string_view key,
                          const std::function<void(uint64_t, std::string_view)>& found,
                          bool* replaced) {
    path_ = path;
    const std::string header = headerFor(key);
    std::string text;
    {
        std::ifstream in(path, std::ios::binary);
        if (in) text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    if (text.compare(0, header.size(), header) == 0) {
        const size_t good = readRecords(text, header.size(), found);
        // Cut a torn tail off, so that what is appended now is read back after the good part.
        if (good < text.size() && ::truncate(path.c_str(), off_t(good)) != 0)
            return "cannot repair the journal '" + path.string() + "': " + std::strerror(errno);
        file_ = std::fopen(path.c_str(), "ab");
    } else {
        if (replaced) *replaced = !text.empty();
        file_ = std::fopen(path.c_str(), "wb");
        if (file_ && (std::fwrite(header.data(), 1, header.size(), file_) != header.size() ||
                      std::fflush(file_) != 0))
            return "cannot write the journal '" + path.string() + "': " + std::strerror(errno);
    }
    if (!file_) return "cannot open the journal '" + path.string() + "': " + std::strerror(errno);
    return {};
}

std::string Journal::append(uint64_t id, std::string_view bytes) {
    const uint64_t size = bytes.size(), hash = recordHash(id, bytes);
    const bool ok = std::fwrite(&id, sizeof id, 1, file_) == 1 &&
                    std::fwrite(&size, sizeof size, 1, file_) == 1 &&
                    std::fwrite(bytes.data(), 1, bytes.size(), file_) == bytes.size() &&
                    std::fwrite(&hash, sizeof hash, 1, file_) == 1 && std::fflush(file_) == 0;
    if (!ok) return "cannot write the journal '" + path_.string() + "': " + std::strerror(errno);
    return {};
}

void Journal::remove() {
    if (file_) std::fclose(file_);
    file_ = nullptr;
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
}

}  // namespace viewer::dist
