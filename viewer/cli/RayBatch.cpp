#include "viewer/cli/RayBatch.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <vector>

#include "primitives/base/ParallelFor.h"
#include "viewer/cli/Cli.h"

namespace viewer {

namespace {

// Rays per block: large enough that starting the threads costs well under 1% of a block,
// small enough that a block's output (up to ~1.5 KB per ray) stays around ten megabytes.
constexpr size_t kBlockRays = 1 << 13;
constexpr size_t kReadChunk = 1 << 20;

struct RayInput {
    csg::Vec3 origin;
    csg::Vec3 dir;  // unit length
};

bool isSeparator(char c) {
    return c == ' ' || c == '\t' || c == ',' || c == '\r';
}

// Parses one line into ray; returns an empty string or the reason it is not a ray.
const char* parseRayLine(std::string_view line, RayInput& ray) {
    double v[6];
    const char* p = line.data();
    const char* end = p + line.size();
    for (double& x : v) {
        while (p != end && isSeparator(*p)) ++p;
        if (p != end && *p == '+') ++p;
        const auto r = std::from_chars(p, end, x);
        if (r.ec != std::errc() || r.ptr == p) return "expected six numbers: ox oy oz dx dy dz";
        if (!std::isfinite(x)) return "a number is not finite";
        p = r.ptr;
    }
    while (p != end && isSeparator(*p)) ++p;
    if (p != end) return "more than six numbers: expected ox oy oz dx dy dz";
    const csg::Vec3 d(v[3], v[4], v[5]);
    const double length = glm::length(d);
    if (!(length > 0.0) || !std::isfinite(length)) return "the direction is zero";
    ray.origin = csg::Vec3(v[0], v[1], v[2]);
    ray.dir = d / length;
    return "";
}

class BlockRunner {
public:
    BlockRunner(const ProbeJson& probe, int threads)
        : threads_(threads), probe_(probe), contexts_(size_t(threads)), outputs_(size_t(threads)) {}

    // Probes rays and writes their lines to stdout in order; false when stdout fails.
    bool run(const std::vector<RayInput>& rays) {
        // One contiguous part per thread at most, each printed to its own buffer.
        const size_t parts = std::min(outputs_.size(), std::max<size_t>(1, rays.size() / 256));
        const size_t per = (rays.size() + parts - 1) / parts;
        csg::parallelFor(parts, threads_, [&](int worker, uint64_t part) {
            csg::QueryContext& ctx = contexts_[size_t(worker)].value;
            std::string& out = outputs_[part];
            out.clear();
            const size_t end = std::min(rays.size(), size_t(part + 1) * per);
            for (size_t i = size_t(part) * per; i < end; ++i) {
                probe_.append(out, rays[i].origin, rays[i].dir, ctx);
                out += '\n';
            }
        });
        for (size_t part = 0; part < parts; ++part)
            if (std::fwrite(outputs_[part].data(), 1, outputs_[part].size(), stdout) !=
                outputs_[part].size())
                return false;
        return true;
    }

private:
    int threads_;
    const ProbeJson& probe_;
    std::vector<csg::WorkerSlot<csg::QueryContext>> contexts_;  // by worker
    std::vector<std::string> outputs_;                          // by part
};

}  // namespace

RayBatchResult probeRayBatch(std::FILE* input, const std::string& inputName, const ProbeJson& probe,
                             int threads, Report& report) {
    RayBatchResult result;
    BlockRunner runner(probe, threads);
    std::vector<RayInput> block;
    block.reserve(kBlockRays);

    auto flush = [&]() {
        if (block.empty()) return true;
        if (!runner.run(block)) {
            report.stdoutFailed();
            result.exitCode = kExitIo;
            return false;
        }
        result.rays += block.size();
        block.clear();
        return true;
    };

    std::string buffer;  // unread input: whole lines are consumed, a partial one is kept
    std::vector<char> chunk(kReadChunk);
    uint32_t lineNumber = 0;
    bool atEof = false;
    while (!atEof) {
        const size_t got = std::fread(chunk.data(), 1, chunk.size(), input);
        if (got < chunk.size()) {
            if (std::ferror(input)) {
                flush();
                report.error(inputName, std::string("cannot read: ") + std::strerror(errno));
                result.exitCode = kExitIo;
                return result;
            }
            atEof = true;
        }
        buffer.append(chunk.data(), got);
        if (atEof && !buffer.empty() && buffer.back() != '\n') buffer += '\n';

        size_t start = 0;
        for (size_t nl; (nl = buffer.find('\n', start)) != std::string::npos; start = nl + 1) {
            ++lineNumber;
            std::string_view line(buffer.data() + start, nl - start);
            const size_t first = line.find_first_not_of(" \t\r");
            if (first == std::string_view::npos || line[first] == '#') continue;
            RayInput ray;
            if (const char* problem = parseRayLine(line, ray); *problem) {
                if (!flush()) return result;
                report.add(io::Diagnostic{inputName, lineNumber, uint32_t(first + 1),
                                          io::Severity::Error, problem});
                result.exitCode = kExitBadModel;
                return result;
            }
            block.push_back(ray);
            if (block.size() == kBlockRays && !flush()) return result;
        }
        buffer.erase(0, start);
    }
    flush();
    if (result.exitCode == kExitOk && std::fflush(stdout) != 0) {
        report.stdoutFailed();
        result.exitCode = kExitIo;
    }
    return result;
}

}  // namespace viewer
