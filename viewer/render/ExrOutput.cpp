#include "viewer/render/ExrOutput.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstdio>
#include <stdexcept>

#include "primitives/base/AtomicFile.h"

namespace viewer::render {

namespace {

// OpenEXR's output stream over the atomic file's FILE*, so the EXR goes to the temporary file
// that commit() renames. OpenEXR reports errors by exception; so does this stream.
class FileStream : public Imf::OStream {
public:
    FileStream(std::FILE* file, const std::string& name)
        : Imf::OStream(name.c_str()), file_(file) {}

    void write(const char c[], int n) override {
        if (std::fwrite(c, 1, size_t(n), file_) != size_t(n))
            throw std::runtime_error("short write");
    }
    uint64_t tellp() override {
        const off_t at = ftello(file_);
        if (at < 0) throw std::runtime_error("cannot tell the write position");
        return uint64_t(at);
    }
    void seekp(uint64_t pos) override {
        if (fseeko(file_, off_t(pos), SEEK_SET) != 0) throw std::runtime_error("cannot seek");
    }

private:
    std::FILE* file_;
};

}  // namespace

std::string writeExr(const std::filesystem::path& path, const LinearImage& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != size_t(image.width) * size_t(image.height) * 3)
        return "cannot write '" + path.string() + "': the image has no pixels";
    csg::AtomicFile file(path);
    if (!file.ok()) return file.error();
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // The pixels are interleaved RGB floats, rows top to bottom (EXR's own order).
        Imf::FrameBuffer frame;
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
        const size_t xStride = 3 * sizeof(float), yStride = xStride * size_t(image.width);
        const char* names[3] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            frame.insert(names[c],
                         Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
        }
        FileStream stream(file.stream(), path.string());
        Imf::OutputFile out(stream, header);
        out.setFrameBuffer(frame);
        out.writePixels(image.height);
    } catch (const std::exception& e) {
        file.fail(e.what());
        return "cannot write '" + path.string() + "': " + e.what();
    }
    if (!file.commit()) return file.error();
    return {};
}

}  // namespace viewer::render
