// The io boundary: reading, parsing, -D overrides and evaluation, with every failure turned
// into a Diagnostic. Evaluation runs on a thread with a large stack, so the depth limits
// (not the operating system) decide how deep a part may recurse.
#include "io/Evaluate.h"

#include <pthread.h>

#include <cctype>
#include <new>

#include "io/Evaluator.h"
#include "io/Parser.h"

namespace io {

namespace {

// Stack for evaluation: deep enough for kMaxNesting parser levels and maxCallDepth calls.
constexpr size_t kEvaluationStackBytes = size_t(1) << 30;
// Without a thread of our own, the caller's stack: assume a small share of its usual 8 MiB.
constexpr size_t kCallerStackBytes = size_t(1) << 20;
// Stack the evaluator leaves unused: room for a leaf call (a builtin, a value walk of
// kMaxListDepth levels, sanitizer frames) after its last stack check.
constexpr size_t kStackReserveBytes = size_t(64) << 20;

// Runs f(usable stack bytes) on a thread with a large stack.
template <class F>
EvaluateResult runWithLargeStack(F& f) {
    struct Job {
        F* f;
        EvaluateResult result;
    } job{&f, {}};
    auto body = [](void* p) -> void* {
        auto* j = static_cast<Job*>(p);
        j->result = (*j->f)(kEvaluationStackBytes - kStackReserveBytes);
        return nullptr;
    };
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setstacksize(&attr, kEvaluationStackBytes);
    pthread_t thread;
    const bool started = pthread_create(&thread, &attr, body, &job) == 0;
    pthread_attr_destroy(&attr);
    if (started)
        pthread_join(thread, nullptr);
    else
        job.result = f(kCallerStackBytes);  // no thread: the caller's stack, a smaller limit
    return std::move(job.result);
}

bool isIdentifier(const std::string& s) {
    if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
    for (size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (!(std::isalnum(c) || c == '_' || (c == '$' && i == 0))) return false;
    }
    return true;
}

EvaluateResult evaluateMain(SourceFiles& sources, uint32_t mainFile, const EvaluateOptions& options,
                            size_t stackBytes) {
    const char stackTop = 0;
    EvaluateResult result;
    auto& diagnostics = result.diagnostics;
    auto fillFiles = [&](Model& model) {
        model.files.clear();
        for (uint32_t i = 0; i < sources.size(); ++i) model.files.push_back(sources.name(i));
    };
    try {
        std::unique_ptr<ParsedFile> parsed = parseFile(sources, mainFile, diagnostics);
        if (!parsed) return result;
        sources.releaseText(mainFile);
        // -D name=value: an assignment appended to the file, so it replaces the file's own
        // assignment of that name in place (OpenSCAD's rule).
        for (const auto& [name, text] : options.defines) {
            if (!isIdentifier(name)) {
                diagnostics.push_back(
                    {"-D", 0, 0, Severity::Error,
                     "'" + name + "' is not a variable name (expected -D name=value)"});
                continue;
            }
            const uint32_t file = sources.add("-D " + name, {}, text);
            ExprPtr value = parseExpression(sources, file, diagnostics);
            if (value)
                parsed->body.add(
                    std::make_unique<AssignmentStmt>(Loc{file, 1, 1}, name, std::move(value)));
        }
        if (hasErrors(diagnostics)) return result;
        Model model;
        {
            Evaluator evaluator(sources, model, diagnostics, options);
            evaluator.setStackLimit(&stackTop, stackBytes);
            try {
                evaluator.run(*parsed);
            } catch (const EvalError& e) {
                diagnostics.push_back(
                    {sources.name(e.loc.file), e.loc.line, e.loc.col, Severity::Error, e.message});
            }
        }
        fillFiles(model);
        if (!hasErrors(diagnostics)) result.model = std::move(model);
    } catch (const std::bad_alloc&) {
        diagnostics.push_back({sources.name(mainFile), 0, 0, Severity::Error,
                               "out of memory while evaluating the part"});
        result.model.reset();
    } catch (const std::exception& e) {
        diagnostics.push_back({sources.name(mainFile), 0, 0, Severity::Error,
                               std::string("internal error: ") + e.what()});
        result.model.reset();
    }
    return result;
}

}  // namespace

EvaluateResult evaluateFile(const std::filesystem::path& file, const EvaluateOptions& options) {
    auto work = [&](size_t stackBytes) -> EvaluateResult {
        SourceFiles sources;
        std::string error;
        auto index = sources.load(file, error);
        if (!index) {
            EvaluateResult r;
            r.diagnostics.push_back({file.string(), 0, 0, Severity::Error, error});
            return r;
        }
        sources.allowFiles(options.allowFiles);  // the main file itself is always read
        return evaluateMain(sources, *index, options, stackBytes);
    };
    return runWithLargeStack(work);
}

EvaluateResult evaluateString(std::string_view source, std::string_view fileName,
                              const EvaluateOptions& options) {
    auto work = [&](size_t stackBytes) -> EvaluateResult {
        SourceFiles sources;
        sources.allowFiles(options.allowFiles);
        const uint32_t index = sources.add(std::string(fileName), std::filesystem::path(fileName),
                                           std::string(source));
        return evaluateMain(sources, index, options, stackBytes);
    };
    return runWithLargeStack(work);
}

Diagnostic diagnosticAt(const Model& model, uint32_t sourceTag, Severity severity,
                        std::string message) {
    const SourceInfo& s = model.source(sourceTag);
    return {model.sourceFile(sourceTag), s.line, s.col, severity, std::move(message)};
}

}  // namespace io
