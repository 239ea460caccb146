#include "viewer/render/Progress.h"

#include <unistd.h>

#include <cstdio>

namespace viewer::render {

namespace {

// A bar redraws often enough to look alive; plain lines stay rare enough not to flood a log.
constexpr std::chrono::milliseconds kBarInterval{100};
constexpr std::chrono::seconds kLineInterval{5};

}  // namespace

ProgressMeter::ProgressMeter(Style style)
    : style_(style), start_(Clock::now()), lastDraw_(start_) {}

ProgressMeter::Style ProgressMeter::styleFor(bool quiet) {
    if (quiet) return Style::Quiet;
    return isatty(STDERR_FILENO) ? Style::Bar : Style::Lines;
}

void ProgressMeter::update(uint64_t done, uint64_t total) {
    if (style_ == Style::Quiet) return;
    const auto now = Clock::now();
    const auto interval = style_ == Style::Bar
                              ? std::chrono::duration_cast<Clock::duration>(kBarInterval)
                              : std::chrono::duration_cast<Clock::duration>(kLineInterval);
    if (now - lastDraw_ < interval) return;
    lastDraw_ = now;
    draw(done, total, false);
}

void ProgressMeter::finish(uint64_t done, uint64_t total, bool interrupted) {
    if (style_ == Style::Quiet) return;
    if (interrupted) {
        if (style_ == Style::Bar && drawn_) std::fputc('\n', stderr);
        std::fprintf(stderr, "render: interrupted at %.0f%%; no file written\n",
                     total ? 100.0 * double(done) / double(total) : 0.0);
        return;
    }
    if (style_ == Style::Bar) {
        draw(done, total, true);
        std::fputc('\n', stderr);
    } else if (drawn_) {
        draw(done, total, true);
    }
}

void ProgressMeter::draw(uint64_t done, uint64_t total, bool final) {
    drawn_ = true;
    const double fraction = total ? double(done) / double(total) : 1.0;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    // The ETA assumes the remaining work goes as fast as the work so far.
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    if (style_ == Style::Lines) {
        std::fprintf(stderr, "render: %3.0f%% after %.1f s, about %.0f s left\n", 100.0 * fraction,
                     elapsed, final ? 0.0 : eta);
        return;
    }
    constexpr int kWidth = 40;
    const int filled = int(fraction * kWidth);
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = '\0';
    if (final)
        std::fprintf(stderr, "\rrender [%s] 100%% in %.1f s          ", bar, elapsed);
    else
        std::fprintf(stderr, "\rrender [%s] %3.0f%%  ETA %.0f s   ", bar, 100.0 * fraction, eta);
    std::fflush(stderr);
}

}  // namespace viewer::render
