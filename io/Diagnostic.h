// Diagnostics are values at the io boundary: every problem in a part (syntax, unknown module,
// wrong argument, bad file) becomes one of these, never an exception escaping io/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace io {

enum class Severity : uint8_t { Error, Warning, Note };

// One message about a place in a source file. line and col are 1-based (col counts UTF-8
// code points); 0 means "no position" (e.g. a file that cannot be opened).
struct Diagnostic {
    std::string file;
    uint32_t line = 0;
    uint32_t col = 0;
    Severity severity = Severity::Error;
    std::string message;
};

// "error", "warning" or "note".
const char* severityName(Severity severity);

// The compiler form "file:line:col: error: message" (positions omitted when 0), no newline.
std::string formatDiagnostic(const Diagnostic& diagnostic);

// All diagnostics as one JSON array of {"file","line","col","severity","message"} objects,
// for --diagnostics=json. Strings are escaped so the output is always valid JSON.
std::string diagnosticsToJson(const std::vector<Diagnostic>& diagnostics);

// True when any diagnostic is an error (the model is then unusable).
bool hasErrors(const std::vector<Diagnostic>& diagnostics);

}  // namespace io
