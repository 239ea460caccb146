#include "viewer/window/PartWatcher.h"

#include <algorithm>
#include <chrono>

#include "viewer/cli/Report.h"

namespace viewer::window {

LoadOutcome loadForView(const CommonOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    LoadOutcome outcome;
    {
        // Text mode, whatever --diagnostics says: a view reloads many times, and one JSON
        // array per load would not make stderr one JSON document anyway.
        Report report(false);
        auto part = std::make_shared<LoadedPart>();
        outcome.exitCode = loadPart(options, report, *part);
        if (outcome.exitCode == kExitOk) outcome.part = std::move(part);
        for (const io::Diagnostic& d : report.diagnostics()) {
            if (d.severity == io::Severity::Error && outcome.firstError.empty())
                outcome.firstError = io::formatDiagnostic(d);
            if (!d.file.empty() && std::find(outcome.namedFiles.begin(), outcome.namedFiles.end(),
                                             d.file) == outcome.namedFiles.end())
                outcome.namedFiles.push_back(d.file);
        }
    }
    if (!outcome.part && outcome.firstError.empty())
        outcome.firstError = options.part + ": error: the part could not be loaded";
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return outcome;
}

std::vector<std::string> filesRead(const io::Model& model) {
    std::vector<std::string> files = model.files;
    for (const io::Model::Texture& texture : model.textures) files.push_back(texture.path);
    return files;
}

PartWatcher::PartWatcher(CommonOptions options, std::function<void()> onLoaded)
    : options_(std::move(options)), onLoaded_(std::move(onLoaded)) {}

PartWatcher::~PartWatcher() = default;  // loader_ joins

PartWatcher::Stamp PartWatcher::stampOf(const std::string& file) {
    Stamp stamp;
    stamp.file = file;
    std::error_code error;
    stamp.time = std::filesystem::last_write_time(file, error);
    if (error) return stamp;
    stamp.size = std::filesystem::file_size(file, error);
    stamp.exists = !error;
    return stamp;
}

void PartWatcher::watch(const std::vector<std::string>& files) {
    stamps_.clear();
    for (const std::string& file : files) {
        bool seen = false;
        for (const Stamp& s : stamps_) seen = seen || s.file == file;
        if (!seen) stamps_.push_back(stampOf(file));
    }
}

void PartWatcher::poll() {
    {
        std::lock_guard lock(mutex_);
        if (loading_) return;
    }
    bool changed = false;
    for (Stamp& stamp : stamps_) {
        const Stamp now = stampOf(stamp.file);
        if (now.exists != stamp.exists || now.time != stamp.time || now.size != stamp.size) {
            changed = true;
            stamp = now;
        }
    }
    // A file being rewritten may be missing or empty for a moment; the next poll sees the end.
    if (!changed) return;
    {
        std::lock_guard lock(mutex_);
        loading_ = true;
    }
    loader_ = std::jthread([this] {
        LoadOutcome outcome = loadForView(options_);
        {
            std::lock_guard lock(mutex_);
            outcome_ = std::move(outcome);
            loading_ = false;
        }
        if (onLoaded_) onLoaded_();
    });
}

std::optional<LoadOutcome> PartWatcher::take() {
    std::lock_guard lock(mutex_);
    std::optional<LoadOutcome> outcome = std::move(outcome_);
    outcome_.reset();
    return outcome;
}

}  // namespace viewer::window
