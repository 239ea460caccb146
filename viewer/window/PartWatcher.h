// Hot reload for the window: polls the modification times of every file the part read (the
// part, its include/use files and its textures) and, when one changes, evaluates and compiles
// the part again on a background thread. A failed load keeps no part: the caller keeps showing
// the last good one and shows the error, and also watches the files the diagnostics name (an
// include added by the edit that broke the part), so fixing any of them reloads.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "viewer/cli/Cli.h"
#include "viewer/cli/LoadPart.h"

namespace viewer::window {

struct LoadOutcome {
    std::shared_ptr<const LoadedPart> part;  // null when the load failed
    int exitCode = kExitOk;                  // loadPart's: kExitIo for an unreadable part
    std::string firstError;                  // "file:line:col: error: message" when it failed
    std::vector<std::string> namedFiles;     // the files the diagnostics name, each once
    double seconds = 0.0;                    // evaluation and compilation
};

// loadPart, with every diagnostic printed on stderr as it is found ("file:line:col: error:
// message", like the other subcommands) and kept for the window. Never throws for a bad part.
LoadOutcome loadForView(const CommonOptions& options);

// Every file the part read: its sources (the part first, then include/use files) and the
// textures its materials read.
std::vector<std::string> filesRead(const io::Model& model);

class PartWatcher {
public:
    // onLoaded runs on the loader thread after each background load (to wake the event loop).
    PartWatcher(CommonOptions options, std::function<void()> onLoaded);
    ~PartWatcher();
    PartWatcher(const PartWatcher&) = delete;
    PartWatcher& operator=(const PartWatcher&) = delete;

    // The files to watch from now on, with their current times (after a successful load:
    // filesRead(model); after a failure, those of the last good part plus namedFiles).
    void watch(const std::vector<std::string>& files);
    // Call a few times a second: when a watched file changed and no load is running, starts
    // one. Cheap: one stat() per file.
    void poll();
    // The outcome of the last background load, once.
    std::optional<LoadOutcome> take();

private:
    struct Stamp {
        std::string file;
        std::filesystem::file_time_type time{};
        uintmax_t size = 0;
        bool exists = false;
    };
    static Stamp stampOf(const std::string& file);

    CommonOptions options_;
    std::function<void()> onLoaded_;
    std::vector<Stamp> stamps_;
    std::mutex mutex_;
    std::optional<LoadOutcome> outcome_;
    bool loading_ = false;  // guarded by mutex_
    std::jthread loader_;
};

}  // namespace viewer::window
