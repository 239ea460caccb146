// Progress on stderr (a render's tiles, the items of an export's loops): a bar with an ETA,
// redrawn in place, when stderr is a terminal; a plain line every few seconds otherwise (logs,
// CI; CSGRAY_PROGRESS_SECONDS sets how many, default 5); nothing when quiet. Only one thread at
// a time calls it (the render's calling thread, the farm's serving thread), so it needs no
// locking.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace viewer::render {

class ProgressMeter {
public:
    enum class Style { Quiet, Lines, Bar };

    // label names the work on every line ("render", "export: the grid's rows").
    explicit ProgressMeter(Style style, std::string label = "render");
    // The style stderr calls for: Bar on a terminal, Lines otherwise, Quiet when asked.
    static Style styleFor(bool quiet);

    // done of total units are finished. Cheap when nothing is due to be printed.
    void update(uint64_t done, uint64_t total);
    // The final state, once something was drawn (work shorter than one interval shows
    // nothing): a finished bar ends its line; interrupted work says so.
    void finish(uint64_t done, uint64_t total, bool interrupted);
    // Starts the meter afresh on other work (the next loop of an export): its clock, its label.
    void restart(std::string label);

private:
    using Clock = std::chrono::steady_clock;
    void draw(uint64_t done, uint64_t total, bool final);

    Style style_;
    std::string label_;
    Clock::duration lineInterval_;
    Clock::time_point start_;
    Clock::time_point lastDraw_;
    bool drawn_ = false;
};

}  // namespace viewer::render
