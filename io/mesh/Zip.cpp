// The zip format's records (PKWARE APPNOTE 6.3, sections 4.3.7, 4.3.12 and 4.3.16), written
// and read as little-endian fields: a local header before each entry's data, then the central
// directory (one header per entry), then the end-of-central-directory record. Reading also
// takes ZIP64's records (4.3.14, 4.3.15, 4.5.3), which lib3mf writes into every package,
// however small (OpenSCAD's 3MF export among them).
#include "io/mesh/Zip.h"

#include <libdeflate.h>

#include <cstdint>
#include <limits>
#include <memory>

namespace io {
namespace {

constexpr uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr uint32_t kCentralHeaderSignature = 0x02014b50;
constexpr uint32_t kEndSignature = 0x06054b50;
constexpr uint32_t kZip64EndSignature = 0x06064b50;
constexpr uint32_t kZip64LocatorSignature = 0x07064b50;
constexpr uint16_t kZip64ExtraId = 0x0001;
constexpr size_t kLocalHeaderBytes = 30;
constexpr size_t kCentralHeaderBytes = 46;
constexpr size_t kEndBytes = 22;
constexpr size_t kZip64LocatorBytes = 20;
constexpr size_t kZip64EndBytes = 56;
constexpr uint16_t kVersion = 20;  // 2.0: deflate, the oldest version every reader takes
constexpr uint16_t kStored = 0, kDeflated = 8;
constexpr uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;  // 1980-01-01, the earliest date
// libdeflate's fastest level: a 3MF of pawn.scad's 1,007,436 triangles is written in 0.43 s
// (median of 3, checks included) and is 10.8 MB, against 1.05 s and 8.7 MB at the default
// level 6 (bench/README.md, mesh files). A slicer reading it does not mind 25 %.
constexpr int kDeflateLevel = 1;
// Deflate cannot expand its input by more than this factor (a 258-byte match in about 2 bits),
// so a larger claimed size is a corrupt or hostile archive, refused before allocating it.
constexpr uint64_t kMaxInflateRatio = 1032;
constexpr uint64_t kMaxField = std::numeric_limits<uint32_t>::max();

void put16(std::string& out, uint16_t v) {
    out += char(v & 0xff);
    out += char(v >> 8);
}
void put32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xff);
}
uint16_t get16(std::string_view in, size_t at) {
    return uint16_t(uint8_t(in[at]) | uint8_t(in[at + 1]) << 8);
}
uint32_t get32(std::string_view in, size_t at) {
    return uint32_t(get16(in, at)) | uint32_t(get16(in, at + 2)) << 16;
}
uint64_t get64(std::string_view in, size_t at) {
    return uint64_t(get32(in, at)) | uint64_t(get32(in, at + 4)) << 32;
}

// A central header's ZIP64 extra field (APPNOTE 4.5.3) holds, in this order, the 64-bit values
// of those of its 32-bit fields that are all ones. Returns false when a needed one is missing.
bool readZip64Extra(std::string_view extra, uint64_t& size, uint64_t& compressed, uint64_t& local) {
    for (size_t at = 0; at + 4 <= extra.size();) {
        const uint16_t id = get16(extra, at), bytes = get16(extra, at + 2);
        if (at + 4 + bytes > extra.size()) return false;
        if (id == kZip64ExtraId) {
            size_t field = at + 4;
            for (uint64_t* value : {&size, &compressed, &local}) {
                if (*value != kMaxField) continue;
                if (field + 8 > at + 4 + bytes) return false;
                *value = get64(extra, field);
                field += 8;
            }
            return true;
        }
        at += 4 + bytes;
    }
    return size != kMaxField && compressed != kMaxField && local != kMaxField;
}

struct CompressorDeleter {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
struct DecompressorDeleter {
    void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

// The fields a local header and a central header share, from "version needed" to the
// extra field's length.
void putCommonFields(std::string& out, uint16_t method, uint32_t crc, size_t compressed,
                     size_t size, size_t nameBytes) {
    put16(out, kVersion);
    put16(out, 0);  // flags: sizes and CRC are in the header, names are plain ASCII
    put16(out, method);
    put16(out, 0);  // time 00:00:00
    put16(out, kDosDate1980);
    put32(out, crc);
    put32(out, uint32_t(compressed));
    put32(out, uint32_t(size));
    put16(out, uint16_t(nameBytes));
    put16(out, 0);  // no extra field
}

}  // namespace

ZipWriteResult writeZip(const std::vector<ZipEntry>& entries) {
    ZipWriteResult result;
    const std::unique_ptr<libdeflate_compressor, CompressorDeleter> compressor(
        libdeflate_alloc_compressor(kDeflateLevel));
    if (!compressor) {
        result.error = "out of memory for the zip compressor";
        return result;
    }
    std::string central;
    std::string& out = result.archive;
    for (const ZipEntry& entry : entries) {
        const size_t size = entry.bytes.size();
        if (size > kMaxField || entry.name.size() > 0xffff || out.size() > kMaxField) {
            result.error = "the 3MF package would need ZIP64 (over 4 GiB), which is not written";
            return result;
        }
        std::string packed(libdeflate_deflate_compress_bound(compressor.get(), size), '\0');
        size_t compressed = libdeflate_deflate_compress(compressor.get(), entry.bytes.data(), size,
                                                        packed.data(), packed.size());
        uint16_t method = kDeflated;
        if (compressed == 0 || compressed >= size) {  // incompressible: stored is smaller
            method = kStored;
            packed = entry.bytes;
            compressed = size;
        }
        packed.resize(compressed);
        const uint32_t crc = libdeflate_crc32(0, entry.bytes.data(), size);

        put32(central, kCentralHeaderSignature);
        put16(central, kVersion);  // version made by: MS-DOS attributes
        putCommonFields(central, method, crc, compressed, size, entry.name.size());
        put16(central, 0);  // no comment
        put16(central, 0);  // disk 0
        put16(central, 0);  // internal attributes
        put32(central, 0);  // external attributes
        put32(central, uint32_t(out.size()));
        central += entry.name;

        put32(out, kLocalHeaderSignature);
        putCommonFields(out, method, crc, compressed, size, entry.name.size());
        out += entry.name;
        out += packed;
    }
    if (out.size() + central.size() > kMaxField || entries.size() > 0xffff) {
        result.error = "the 3MF package would need ZIP64 (over 4 GiB), which is not written";
        return result;
    }
    const uint32_t centralOffset = uint32_t(out.size());
    out += central;
    put32(out, kEndSignature);
    put16(out, 0);  // this disk
    put16(out, 0);  // the disk where the central directory starts
    put16(out, uint16_t(entries.size()));
    put16(out, uint16_t(entries.size()));
    put32(out, uint32_t(central.size()));
    put32(out, centralOffset);
    put16(out, 0);  // no comment
    return result;
}

ZipReadResult readZip(std::string_view archive) {
    ZipReadResult result;
    auto fail = [&](std::string why) {
        result.entries.clear();
        result.error = "not a readable zip package: " + std::move(why);
        return result;
    };

    // Step 1: the end record, searched backwards past a comment of up to 64 KiB.
    if (archive.size() < kEndBytes) return fail("too short");
    size_t end = archive.size() - kEndBytes;
    const size_t lowest = end > 0xffff ? end - 0xffff : 0;
    while (get32(archive, end) != kEndSignature) {
        if (end == lowest) return fail("no end-of-central-directory record");
        --end;
    }
    if (get16(archive, end + 4) != 0 || get16(archive, end + 6) != 0)
        return fail("multi-disk archives are not read");
    uint64_t count = get16(archive, end + 10);
    uint64_t centralSize = get32(archive, end + 12);
    uint64_t centralOffset = get32(archive, end + 16);
    // ZIP64: the locator just before the end record points to the 64-bit end record.
    size_t directoryEnd = end;
    if (end >= kZip64LocatorBytes &&
        get32(archive, end - kZip64LocatorBytes) == kZip64LocatorSignature) {
        const uint64_t record = get64(archive, end - kZip64LocatorBytes + 8);
        if (record > end - kZip64LocatorBytes ||
            end - kZip64LocatorBytes - record < kZip64EndBytes ||
            get32(archive, size_t(record)) != kZip64EndSignature)
            return fail("the ZIP64 end record is missing");
        count = get64(archive, size_t(record) + 32);
        centralSize = get64(archive, size_t(record) + 40);
        centralOffset = get64(archive, size_t(record) + 48);
        directoryEnd = size_t(record);
    }
    if (centralOffset > directoryEnd || centralSize > directoryEnd - centralOffset)
        return fail("the central directory lies outside the file");

    // Step 2: each central header names an entry and where its local header is.
    const std::unique_ptr<libdeflate_decompressor, DecompressorDeleter> decompressor(
        libdeflate_alloc_decompressor());
    if (!decompressor) return fail("out of memory for the decompressor");
    size_t at = centralOffset;
    const size_t centralEnd = centralOffset + centralSize;
    for (size_t i = 0; i < count; ++i) {
        if (centralEnd - at < kCentralHeaderBytes || get32(archive, at) != kCentralHeaderSignature)
            return fail("central directory entry " + std::to_string(i + 1) + " is broken");
        const uint16_t flags = get16(archive, at + 8);
        const uint16_t method = get16(archive, at + 10);
        const uint32_t crc = get32(archive, at + 16);
        uint64_t compressed = get32(archive, at + 20);
        uint64_t size = get32(archive, at + 24);
        const size_t nameBytes = get16(archive, at + 28);
        const size_t extraBytes = get16(archive, at + 30);
        const size_t skip = nameBytes + extraBytes + get16(archive, at + 32);
        uint64_t local = get32(archive, at + 42);
        if (centralEnd - at - kCentralHeaderBytes < skip)
            return fail("central directory entry " + std::to_string(i + 1) + " is broken");
        ZipEntry entry;
        entry.name = std::string(archive.substr(at + kCentralHeaderBytes, nameBytes));
        const std::string which = "entry '" + entry.name + "'";
        if (!readZip64Extra(archive.substr(at + kCentralHeaderBytes + nameBytes, extraBytes), size,
                            compressed, local))
            return fail(which + ": its ZIP64 sizes are missing");
        at += kCentralHeaderBytes + skip;
        if (flags & 1) return fail(which + " is encrypted");

        // Step 3: the data after the local header (whose own name and extra lengths count).
        if (local > centralOffset || centralOffset - local < kLocalHeaderBytes ||
            get32(archive, local) != kLocalHeaderSignature)
            return fail(which + ": its local header is missing");
        const uint64_t data = local + kLocalHeaderBytes + get16(archive, size_t(local) + 26) +
                              get16(archive, size_t(local) + 28);
        if (data > centralOffset || centralOffset - data < compressed)
            return fail(which + ": its data lies outside the file");
        const std::string_view packed = archive.substr(size_t(data), size_t(compressed));
        if (method == kStored) {
            if (compressed != size) return fail(which + ": stored with two different sizes");
            entry.bytes = std::string(packed);
        } else if (method == kDeflated) {
            if (size > compressed * kMaxInflateRatio + 1024)
                return fail(which + ": its size is more than deflate can produce");
            entry.bytes.assign(size_t(size), '\0');
            if (libdeflate_deflate_decompress(decompressor.get(), packed.data(), packed.size(),
                                              entry.bytes.data(), entry.bytes.size(),
                                              nullptr) != LIBDEFLATE_SUCCESS)
                return fail(which + ": its deflate data is corrupt");
        } else {
            return fail(which + ": compression method " + std::to_string(method) +
                        " (only stored and deflate are read)");
        }
        if (libdeflate_crc32(0, entry.bytes.data(), entry.bytes.size()) != crc)
            return fail(which + ": CRC-32 mismatch");
        result.entries.push_back(std::move(entry));
    }
    return result;
}

}  // namespace io
