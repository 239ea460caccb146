#include "viewer/render/Progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace viewer::render {

namespace {

// A bar redraws often enough to look alive; plain lines stay rare enough not to flood a log.
constexpr std::chrono::milliseconds kBarInterval{100};
constexpr double kLineSeconds = 5.0;

// The interval of plain lines: CSGRAY_PROGRESS_SECONDS when it is a number >= 0 (0: every
// update), else kLineSeconds.
std::chrono::steady_clock::duration lineInterval() {
    double seconds = kLineSeconds;
    if (const char* value = std::getenv("CSGRAY_PROGRESS_SECONDS")) {
        char* end = nullptr;
        const double v = std::strtod(value, &end);
        if (end != value && *end == '\0' && v >= 0.0 && v <= 1e6) seconds = v;
    }
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(seconds));
}

}  // namespace

ProgressMeter::ProgressMeter(Style style, std::string label)
    : style_(style),
      label_(std::move(label)),
      lineInterval_(lineInterval()),
      start_(Clock::now()),
      lastDraw_(start_) {}

void ProgressMeter::restart(std::string label) {
    label_ = std::move(label);
    start_ = lastDraw_ = Clock::now();
    drawn_ = false;
}

ProgressMeter::Style ProgressMeter::styleFor(bool quiet) {
    if (quiet) return Style::Quiet;
    return isatty(STDERR_FILENO) ? Style::Bar : Style::Lines;
}

void ProgressMeter::update(uint64_t done, uint64_t total) {
    if (style_ == Style::Quiet) return;
    const auto now = Clock::now();
    const auto interval = style_ == Style::Bar
                              ? std::chrono::duration_cast<Clock::duration>(kBarInterval)
                              : lineInterval_;
    if (now - lastDraw_ < interval) return;
    lastDraw_ = now;
    draw(done, total, false);
}

void ProgressMeter::finish(uint64_t done, uint64_t total, bool interrupted) {
    if (style_ == Style::Quiet) return;
    if (interrupted) {
        if (style_ == Style::Bar && drawn_) std::fputc('\n', stderr);
        std::fprintf(stderr, "%s: interrupted at %.0f%%; no file written\n", label_.c_str(),
                     total ? 100.0 * double(done) / double(total) : 0.0);
        return;
    }
    // Work too short to have been drawn (under one interval) leaves no line.
    if (!drawn_) return;
    draw(done, total, true);
    if (style_ == Style::Bar) std::fputc('\n', stderr);
}

void ProgressMeter::draw(uint64_t done, uint64_t total, bool final) {
    drawn_ = true;
    const double fraction = total ? double(done) / double(total) : 1.0;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    // The ETA assumes the remaining work goes as fast as the work so far.
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    if (style_ == Style::Lines) {
        std::fprintf(stderr, "%s: %3.0f%% after %.1f s, about %.0f s left\n", label_.c_str(),
                     100.0 * fraction, elapsed, final ? 0.0 : eta);
        return;
    }
    constexpr int kWidth = 40;
    const int filled = int(fraction * kWidth);
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = '\0';
    if (final)
        std::fprintf(stderr, "\r%s [%s] 100%% in %.1f s          ", label_.c_str(), bar, elapsed);
    else
        std::fprintf(stderr, "\r%s [%s] %3.0f%%  ETA %.0f s   ", label_.c_str(), bar,
                     100.0 * fraction, eta);
    std::fflush(stderr);
}

}  // namespace viewer::render
