#include "primitives/base/AtomicFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace csg {

namespace {

std::string describeErrno(const std::string& what, const std::filesystem::path& path) {
    return what + " '" + path.string() + "': " + std::strerror(errno);
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
    // mkstemp picks a unique name, so two renders into one folder never share a temp file.
    const std::filesystem::path dir =
        target_.has_parent_path() ? target_.parent_path() : std::filesystem::path(".");
    std::string pattern = (dir / ("." + target_.filename().string() + ".tmp-XXXXXX")).string();
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) {
        error_ = describeErrno("cannot create a file in", dir);
        return;
    }
    temp_ = pattern;
    // mkstemp creates the file 0600; a finished output gets the usual mode (umask applied).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    file_ = ::fdopen(fd, "wb");
    if (!file_) {
        error_ = describeErrno("cannot open", temp_);
        ::close(fd);
        std::filesystem::remove(temp_);
        temp_.clear();
    }
}

AtomicFile::~AtomicFile() {
    discard();
}

void AtomicFile::fail(std::string reason) {
    if (error_.empty()) error_ = std::move(reason);
    discard();
}

void AtomicFile::discard() {
    if (file_) {
        std::fclose(file_);
        file_ = nullptr;
    }
    if (!temp_.empty()) {
        std::error_code ignored;
        std::filesystem::remove(temp_, ignored);
        temp_.clear();
    }
}

bool AtomicFile::commit() {
    if (!file_) {
        if (error_.empty()) error_ = "the file was not open";
        return false;
    }
    // A full disk often shows only at flush or close, so every step is checked.
    const bool written =
        std::fflush(file_) == 0 && !std::ferror(file_) && ::fsync(::fileno(file_)) == 0;
    if (!written) {
        error_ = describeErrno("cannot write", target_);
        discard();
        return false;
    }
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) {
        error_ = describeErrno("cannot write", target_);
        discard();
        return false;
    }
    if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
        error_ = describeErrno("cannot write", target_);
        discard();
        return false;
    }
    temp_.clear();
    return true;
}

std::string writeFileAtomically(const std::filesystem::path& target, std::string_view bytes) {
    AtomicFile file(target);
    if (!file.ok()) return file.error();
    if (std::fwrite(bytes.data(), 1, bytes.size(), file.stream()) != bytes.size()) {
        file.fail("cannot write '" + target.string() + "': short write");
        return file.error();
    }
    if (!file.commit()) return file.error();
    return {};
}

}  // namespace csg
