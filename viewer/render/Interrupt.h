// Ctrl-C during a render: the SIGINT handler only sets an atomic flag, which the workers
// poll between tiles; the command then stops, writes nothing and exits with 130 (128 + SIGINT,
// the shell's convention). A second Ctrl-C kills the process the ordinary way.
#pragma once

#include <atomic>
#include <csignal>

namespace viewer::render {

// The flag the handler sets. Lock-free, so it is safe to set from a signal handler.
std::atomic<bool>& interruptRequested();

// Installs the handler (for one SIGINT) and clears the flag; the destructor restores the
// previous disposition.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    struct sigaction previous_ {};
};

inline constexpr int kExitInterrupted = 130;

}  // namespace viewer::render
