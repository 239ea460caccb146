#include "primitives/base/ReadFile.h"

#include <fstream>

namespace csg {

ReadFailure readWholeFile(const std::filesystem::path& path, std::string& bytes) {
    bytes.clear();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return ReadFailure::IsDirectory;
    std::ifstream in(path, std::ios::binary);
    if (!in) return ReadFailure::CannotOpen;
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) return ReadFailure::CannotRead;
    if (size > 0) {
        bytes.resize(static_cast<size_t>(size));
        in.seekg(0);
        in.read(bytes.data(), size);
    }
    return in.bad() ? ReadFailure::CannotRead : ReadFailure::None;
}

}  // namespace csg
