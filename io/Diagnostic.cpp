#include "io/Diagnostic.h"

#include <cstdio>

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

// JSON string escaping; bytes are passed through as UTF-8 except controls.
static void appendJsonString(std::string& out, const std::string& s) {
    out += '"';
    for (char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\r':
                out += "\\r";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buffer[8];
                    std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
                    out += buffer;
                } else {
                    out += c;
                }
        }
    }
    out += '"';
}

std::string diagnosticsToJson(const std::vector<Diagnostic>& diagnostics) {
    std::string out = "[";
    for (size_t i = 0; i < diagnostics.size(); ++i) {
        const Diagnostic& d = diagnostics[i];
        if (i) out += ",";
        out += "{\"file\":";
        appendJsonString(out, d.file);
        out += ",\"line\":" + std::to_string(d.line) + ",\"col\":" + std::to_string(d.col) +
               ",\"severity\":\"" + severityName(d.severity) + "\",\"message\":";
        appendJsonString(out, d.message);
        out += "}";
    }
    out += "]";
    return out;
}

bool hasErrors(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics)
        if (d.severity == Severity::Error) return true;
    return false;
}

}  // namespace io
