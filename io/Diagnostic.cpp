#include "io/Diagnostic.h"

#include "primitives/base/Json.h"

namespace io {

const char* severityName(Severity severity) {
    switch (severity) {
        case Severity::Error:
            return "error";
        case Severity::Warning:
            return "warning";
        case Severity::Note:
            return "note";
    }
    return "error";
}

std::string formatDiagnostic(const Diagnostic& d) {
    std::string out = d.file;
    if (d.line > 0) {
        out += ":" + std::to_string(d.line);
        if (d.col > 0) out += ":" + std::to_string(d.col);
    }
    if (!out.empty()) out += ": ";
    out += severityName(d.severity);
    out += ": ";
    out += d.message;
    return out;
}

std::string diagnosticsToJson(const std::vector<Diagnostic>& diagnostics) {
    std::string out;
    csg::JsonWriter json(out);
    json.beginArray();
    for (const Diagnostic& d : diagnostics) {
        json.beginObject();
        json.key("file").value(d.file);
        json.key("line").value(static_cast<uint64_t>(d.line));
        json.key("col").value(static_cast<uint64_t>(d.col));
        json.key("severity").value(severityName(d.severity));
        json.key("message").value(d.message);
        json.endObject();
    }
    json.endArray();
    return out;
}

bool hasErrors(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics)
        if (d.severity == Severity::Error) return true;
    return false;
}

}  // namespace io
