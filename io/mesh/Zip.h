// The zip container of 3MF files (a package of XML parts): writing deflated entries and reading
// stored or deflated ones, by libdeflate (already csgray's PNG compressor). Only what a 3MF
// package needs: no ZIP64 (an archive and every entry below 4 GiB), no encryption, no
// multi-disk archives. The writer's bytes depend only on its entries (fixed 1980-01-01 dates),
// so an export is reproducible.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace io {

struct ZipEntry {
    std::string name;   // the path inside the archive, '/'-separated, no leading '/'
    std::string bytes;  // uncompressed
};

// The archive of entries, in their order, each deflated (or stored when that is no larger).
// Returns an error instead when an entry or the archive would need ZIP64.
struct ZipWriteResult {
    std::string archive;
    std::string error;  // empty on success
};
ZipWriteResult writeZip(const std::vector<ZipEntry>& entries);

// The entries of an archive, by its central directory, each inflated and checked against its
// CRC-32. Any inconsistency (truncated records, offsets out of range, an unknown compression
// method, a size that deflate cannot produce from its input) is an error, never a crash.
struct ZipReadResult {
    std::vector<ZipEntry> entries;
    std::string error;  // empty on success
};
ZipReadResult readZip(std::string_view archive);

}  // namespace io
