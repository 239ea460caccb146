// Render progress on stderr: a bar with an ETA, redrawn in place, when stderr is a terminal; a
// plain line every few seconds otherwise (logs, CI); nothing when quiet. Only the thread that
// owns the meter calls it (the render's calling thread), so it needs no locking.
#pragma once

#include <chrono>
#include <cstdint>

namespace viewer::render {

class ProgressMeter {
public:
    enum class Style { Quiet, Lines, Bar };

    explicit ProgressMeter(Style style);
    // The style stderr calls for: Bar on a terminal, Lines otherwise, Quiet when asked.
    static Style styleFor(bool quiet);

    // done of total units are finished. Cheap when nothing is due to be printed.
    void update(uint64_t done, uint64_t total);
    // The final state: a finished bar ends its line; interrupted work says so.
    void finish(uint64_t done, uint64_t total, bool interrupted);

private:
    using Clock = std::chrono::steady_clock;
    void draw(uint64_t done, uint64_t total, bool final);

    Style style_;
    Clock::time_point start_;
    Clock::time_point lastDraw_;
    bool drawn_ = false;
};

}  // namespace viewer::render
