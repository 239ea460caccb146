#include "viewer/window/PartWatcher.h"

#include <chrono>
#include <cstdio>

#include "io/Evaluate.h"

namespace viewer::window {

namespace {

void printDiagnostic(const io::Diagnostic& diagnostic, LoadOutcome& outcome) {
    const std::string text = io::formatDiagnostic(diagnostic);
    std::fprintf(stderr, "%s\n", text.c_str());
    if (diagnostic.severity == io::Severity::Error && outcome.firstError.empty())
        outcome.firstError = text;
}

}  // namespace

LoadOutcome loadForView(const CommonOptions& options) {
    // The same steps as loadPart, but the first error is kept for the window's title.
    const auto start = std::chrono::steady_clock::now();
    LoadOutcome outcome;
    io::EvaluateOptions evaluateOptions;
    evaluateOptions.defines = options.defines;
    io::EvaluateResult result = io::evaluateFile(options.part, evaluateOptions);
    for (const io::Diagnostic& d : result.diagnostics) printDiagnostic(d, outcome);
    if (result.ok()) {
        auto part = std::make_shared<LoadedPart>();
        part->model = std::move(*result.model);
        try {
            part->scene = csg::Scene::compile(part->model.root);
            outcome.part = std::move(part);
        } catch (const csg::CompileError& e) {
            printDiagnostic(io::diagnosticAt(part->model, e.source, io::Severity::Error, e.what()),
                            outcome);
        }
    }
    if (!outcome.part && outcome.firstError.empty())
        outcome.firstError = options.part + ": error: the part could not be loaded";
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return outcome;
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
