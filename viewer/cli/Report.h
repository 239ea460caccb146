// Where a subcommand's diagnostics go: as text, each is printed on stderr when it arrives
// ("file:line:col: error: message"); as JSON, they are collected and printed on stderr as one
// array when the command ends, so stderr is one valid JSON document. stdout is never touched.
#pragma once

#include <string>
#include <vector>

#include "io/Diagnostic.h"

namespace viewer {

class Report {
public:
    explicit Report(bool json) : json_(json) {}
    ~Report() { finish(); }
    Report(const Report&) = delete;
    Report& operator=(const Report&) = delete;

    void add(io::Diagnostic diagnostic);
    void addAll(const std::vector<io::Diagnostic>& diagnostics);
    // An error without a source position (an output file that cannot be written).
    void error(std::string file, std::string message);
    // Reports that stdout could not be written (errno says why).
    void stdoutFailed();
    // Writes text to stdout and flushes it; on failure reports it and returns false.
    bool writeStdout(const std::string& text);
    // An echo() line from the part: plain on stderr, or a note in JSON mode.
    void echo(const std::string& line);
    // Prints the JSON array (once); does nothing in text mode.
    void finish();
    // Every diagnostic added so far (not echo lines), in order, in either mode: for a caller
    // that also shows them elsewhere (the view's title and which files it watches).
    const std::vector<io::Diagnostic>& diagnostics() const { return diagnostics_; }

    // On every MPI rank but rank 0: print errors only, since rank 0 prints the same part's
    // warnings and echo() lines once for the job (process-wide, set before any Report).
    static void showErrorsOnly() { errorsOnly_ = true; }

private:
    static inline bool errorsOnly_ = false;
    bool json_;
    bool finished_ = false;
    std::vector<io::Diagnostic> collected_;  // JSON mode: diagnostics and echo notes
    std::vector<io::Diagnostic> diagnostics_;
};

}  // namespace viewer
