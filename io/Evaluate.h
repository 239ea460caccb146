// The entry points of the part language: OpenSCAD's language (its CSG subset, with OpenSCAD's
// semantics) plus csgray's scene modules, evaluated into an io::Model. Nothing throws out of
// these functions: every problem comes back as a Diagnostic.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/Diagnostic.h"
#include "io/Faceting.h"
#include "io/Model.h"

namespace io {

struct EvaluateOptions {
    // -D name=value overrides, in command-line order. value is parsed as an expression; the
    // override replaces the file's top-level assignment of name (as OpenSCAD's -D does).
    std::vector<std::pair<std::string, std::string>> defines;
    // Receives each echo() line ("ECHO: ..." exactly as OpenSCAD prints it, no newline).
    // Unset: the line goes to stderr.
    std::function<void(const std::string&)> echo;
    // Module and function calls nested deeper than this are an error (not a stack overflow).
    uint32_t maxCallDepth = 10000;
    // Evaluation steps beyond this are an error at the place the budget ran out, so no part can
    // hang the evaluator or take all memory. A step is about one expression node, loop
    // iteration, or list element or character produced or walked (a statement counts 64, a
    // function call 8). The budget bounds a run's time and memory to what an ordinary
    // machine affords (bench/README.md, the evaluator's work budget).
    uint64_t maxSteps = 500'000'000;
    // False: include <f> and use <f> are errors, for evaluating untrusted text (the fuzzer).
    bool allowFiles = true;
    // What cylinder() and sphere() become: OpenSCAD's polyhedra or exact quadrics (--curves;
    // see CurveMode in io/Faceting.h).
    CurveMode curves = CurveMode::Auto;
    // $t, OpenSCAD's animation time in [0, 1): frame / frames under --animate (render --frames).
    double time = 0.0;
};

struct EvaluateResult {
    // Present exactly when no diagnostic is an error.
    std::optional<Model> model;
    // Errors and warnings in the order they were found.
    std::vector<Diagnostic> diagnostics;

    bool ok() const { return model.has_value(); }
};

// Reads, lexes, parses and evaluates a part file; include/use paths resolve relative to it.
// An unreadable file is an error diagnostic with line 0.
EvaluateResult evaluateFile(const std::filesystem::path& file, const EvaluateOptions& options = {});

// Same, from text in memory; fileName labels diagnostics and is the base for include/use
// (relative names resolve against the current directory when it has no directory part).
EvaluateResult evaluateString(std::string_view source, std::string_view fileName = "<string>",
                              const EvaluateOptions& options = {});

// Turns a csg::CompileError's source tag into a diagnostic at that node's statement.
Diagnostic diagnosticAt(const Model& model, uint32_t sourceTag, Severity severity,
                        std::string message);

}  // namespace io
