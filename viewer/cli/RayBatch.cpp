#include "viewer/cli/RayBatch.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string_view>
#include <vector>

#include "primitives/base/ParallelFor.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/dist/TaskFarm.h"

namespace viewer {

namespace {

// Rays per block: large enough that starting the threads costs well under 1% of a block,
// small enough that a block's output (up to ~1.5 KB per ray) stays around ten megabytes.
constexpr size_t kBlockRays = 1 << 13;
constexpr size_t kReadChunk = 1 << 20;
// Rays per task of the MPI farm: a task's output (up to ~1.5 MB) is one message, and a few
// tasks per thread keep the ranks balanced however the rays' costs vary.
constexpr size_t kTaskRays = 1 << 10;

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

// The rays of the input, one at a time, in order: whole lines are parsed out of large reads.
class RayReader {
public:
    enum class Got { Ray, End, BadLine, ReadError };

    RayReader(std::FILE* input) : input_(input), chunk_(kReadChunk) {}

    Got next(RayInput& ray) {
        for (;;) {
            const size_t nl = buffer_.find('\n', start_);
            if (nl == std::string::npos) {
                if (atEof_) return Got::End;
                if (!refill()) return Got::ReadError;
                continue;
            }
            ++lineNumber_;
            const std::string_view line(buffer_.data() + start_, nl - start_);
            start_ = nl + 1;
            const size_t first = line.find_first_not_of(" \t\r");
            if (first == std::string_view::npos || line[first] == '#') continue;
            if (const char* problem = parseRayLine(line, ray); *problem) {
                problem_ = problem;
                column_ = uint32_t(first + 1);
                return Got::BadLine;
            }
            return Got::Ray;
        }
    }

    // Where the bad line is and what is wrong with it (after Got::BadLine).
    uint32_t lineNumber() const { return lineNumber_; }
    uint32_t column() const { return column_; }
    const char* problem() const { return problem_; }

private:
    // Reads the next chunk after the unread rest; a last line without '\n' gets one.
    bool refill() {
        buffer_.erase(0, start_);
        start_ = 0;
        const size_t got = std::fread(chunk_.data(), 1, chunk_.size(), input_);
        if (got < chunk_.size()) {
            if (std::ferror(input_)) return false;
            atEof_ = true;
        }
        buffer_.append(chunk_.data(), got);
        if (atEof_ && !buffer_.empty() && buffer_.back() != '\n') buffer_ += '\n';
        return true;
    }

    std::FILE* input_;
    std::vector<char> chunk_;
    std::string buffer_;  // unread input: whole lines are consumed, a partial one is kept
    size_t start_ = 0;
    bool atEof_ = false;
    uint32_t lineNumber_ = 0, column_ = 0;
    const char* problem_ = "";
};

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

    RayReader reader(input);
    RayInput ray;
    for (;;) {
        const RayReader::Got got = reader.next(ray);
        if (got == RayReader::Got::End) break;
        if (got == RayReader::Got::ReadError) {
            flush();
            report.error(inputName, std::string("cannot read: ") + std::strerror(errno));
            result.exitCode = kExitIo;
            return result;
        }
        if (got == RayReader::Got::BadLine) {
            if (!flush()) return result;
            report.add(io::Diagnostic{inputName, reader.lineNumber(), reader.column(),
                                      io::Severity::Error, reader.problem()});
            result.exitCode = kExitBadModel;
            return result;
        }
        block.push_back(ray);
        if (block.size() == kBlockRays && !flush()) return result;
    }
    flush();
    if (result.exitCode == kExitOk && std::fflush(stdout) != 0) {
        report.stdoutFailed();
        result.exitCode = kExitIo;
    }
    return result;
}

namespace {

// Rank 0's rays: read in tasks of kTaskRays, their lines written in input order as they come
// back (a task that arrives early waits in `waiting_` for the ones before it).
class RaySource : public dist::TaskSource {
public:
    RaySource(std::FILE* input) : reader_(input) {}

    bool next(dist::Task& task) override {
        if (stopped_) return false;
        task.input.clear();
        RayInput ray;
        size_t rays = 0;
        while (rays < kTaskRays) {
            got_ = reader_.next(ray);
            if (got_ != RayReader::Got::Ray) {
                if (got_ == RayReader::Got::ReadError) readErrno_ = errno;
                stopped_ = true;
                break;
            }
            task.input.append(reinterpret_cast<const char*>(&ray), sizeof ray);
            ++rays;
        }
        if (rays == 0) return false;
        task.id = tasks_++;
        rays_ += rays;
        return true;
    }

    void finished(uint64_t id, std::string&& lines) override {
        waiting_.emplace(id, std::move(lines));
        for (auto first = waiting_.begin(); first != waiting_.end() && first->first == written_;
             first = waiting_.erase(first), ++written_) {
            if (writeFailed_) continue;
            const std::string& text = first->second;
            if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size()) {
                writeErrno_ = errno;
                writeFailed_ = stopped_ = true;
            }
        }
    }

    RayReader reader_;
    RayReader::Got got_ = RayReader::Got::Ray;
    bool stopped_ = false, writeFailed_ = false;
    int readErrno_ = 0, writeErrno_ = 0;
    uint64_t tasks_ = 0, written_ = 0, rays_ = 0;
    std::map<uint64_t, std::string> waiting_;
};

}  // namespace

RayBatchResult probeRayBatchOnRanks(const dist::Ranks& ranks, std::FILE* input,
                                    const std::string& inputName, const ProbeJson& probe,
                                    int threads, Report& report) {
    std::unique_ptr<RaySource> source;
    if (ranks.root()) source = std::make_unique<RaySource>(input);
    std::vector<csg::WorkerSlot<csg::QueryContext>> contexts(static_cast<size_t>(threads));
    dist::runFarm(ranks, source.get(), threads,
                  [&](int worker, const dist::Task& task, std::string& lines) {
                      csg::QueryContext& ctx = contexts[size_t(worker)].value;
                      const size_t count = task.input.size() / sizeof(RayInput);
                      for (size_t i = 0; i < count; ++i) {
                          RayInput ray;
                          std::memcpy(&ray, task.input.data() + i * sizeof ray, sizeof ray);
                          probe.append(lines, ray.origin, ray.dir, ctx);
                          lines += '\n';
                      }
                  });
    RayBatchResult result;
    if (!ranks.root()) return result;
    result.rays = source->rays_;
    if (source->writeFailed_ || std::fflush(stdout) != 0) {
        if (source->writeFailed_) errno = source->writeErrno_;
        report.stdoutFailed();
        result.exitCode = kExitIo;
    } else if (source->got_ == RayReader::Got::ReadError) {
        report.error(inputName, std::string("cannot read: ") + std::strerror(source->readErrno_));
        result.exitCode = kExitIo;
    } else if (source->got_ == RayReader::Got::BadLine) {
        const RayReader& r = source->reader_;
        report.add(io::Diagnostic{inputName, r.lineNumber(), r.column(), io::Severity::Error,
                                  r.problem()});
        result.exitCode = kExitBadModel;
    }
    return result;
}

}  // namespace viewer
