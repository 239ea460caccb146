#include "viewer/cli/Report.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace viewer {

void Report::add(io::Diagnostic diagnostic) {
    diagnostics_.push_back(diagnostic);
    if (errorsOnly_ && diagnostic.severity != io::Severity::Error) return;
    if (json_) {
        collected_.push_back(std::move(diagnostic));
        return;
    }
    const std::string line = io::formatDiagnostic(diagnostic) + "\n";
    std::fputs(line.c_str(), stderr);
}

void Report::addAll(const std::vector<io::Diagnostic>& diagnostics) {
    for (const io::Diagnostic& d : diagnostics) add(d);
}

void Report::error(std::string file, std::string message) {
    add(io::Diagnostic{std::move(file), 0, 0, io::Severity::Error, std::move(message)});
}

void Report::stdoutFailed() {
    error("<stdout>", std::string("cannot write: ") + std::strerror(errno));
}

bool Report::writeStdout(const std::string& text) {
    if (std::fwrite(text.data(), 1, text.size(), stdout) == text.size() && std::fflush(stdout) == 0)
        return true;
    stdoutFailed();
    return false;
}

void Report::echo(const std::string& line) {
    if (errorsOnly_) return;
    if (json_) {
        collected_.push_back(io::Diagnostic{"", 0, 0, io::Severity::Note, line});
        return;
    }
    std::fputs((line + "\n").c_str(), stderr);
}

void Report::finish() {
    if (!json_ || finished_) return;
    finished_ = true;
    const std::string text = io::diagnosticsToJson(collected_) + "\n";
    std::fputs(text.c_str(), stderr);
}

}  // namespace viewer
