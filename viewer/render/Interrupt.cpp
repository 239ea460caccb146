#include "viewer/render/Interrupt.h"

#include <csignal>

namespace viewer::render {

namespace {

std::atomic<bool> gInterrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void onInterrupt(int) {
    gInterrupted.store(true, std::memory_order_relaxed);
}

}  // namespace

std::atomic<bool>& interruptRequested() {
    return gInterrupted;
}

InterruptGuard::InterruptGuard() {
    gInterrupted.store(false);
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    // One-shot: after the first Ctrl-C the default action is back, so a second one kills a
    // render that is slow to stop.
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &previous_);
}

InterruptGuard::~InterruptGuard() {
    sigaction(SIGINT, &previous_, nullptr);
}

}  // namespace viewer::render
