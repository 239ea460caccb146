// Command-line plumbing shared by the csgray subcommands: exit codes, the options every
// subcommand takes (the part, -D, --curves, --diagnostics, --help), an argument cursor, and parsers
// for the value forms (X,Y,Z vectors, WxH sizes). Each subcommand parses its own options with it.
#pragma once

#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/Faceting.h"
#include "primitives/Polyhedron.h"
#include "primitives/base/Accel.h"
#include "primitives/base/Math.h"

namespace viewer {

// The contract of DESIGN.md: 0 ok, 1 bad model or input, 2 bad usage, 3 I/O.
enum ExitCode : int { kExitOk = 0, kExitBadModel = 1, kExitUsage = 2, kExitIo = 3 };

// A command line that cannot be understood; main prints it with a pointer to --help, exit 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// What every subcommand that reads a part accepts.
struct CommonOptions {
    std::string part;                                                   // the part file
    std::vector<std::pair<std::string, std::string>> defines;           // -D name=value, in order
    bool jsonDiagnostics = false;                                       // --diagnostics=json
    io::CurveMode curves = io::CurveMode::Auto;                         // --curves
    csg::Accel accel = csg::Accel::Sah;                                 // --accel
    csg::PolygonMethod polygonMethod = csg::PolygonMethod::Watertight;  // --polygon-method
    bool slabs = false;                                                 // --bounds=slabs
    bool help = false;                                                  // --help or -h
    double time = 0.0;  // $t (render --frames sets it per frame; no option of its own)
};

// Walks the arguments of one subcommand (argv after the subcommand's name).
class ArgCursor {
public:
    explicit ArgCursor(std::span<const std::string> args) : args_(args) {}

    bool done() const { return index_ >= args_.size(); }
    const std::string& peek() const { return args_[index_]; }
    const std::string& take() { return args_[index_++]; }

    // When the current argument is `name VALUE` or `name=VALUE`, consumes it and returns VALUE.
    // A missing VALUE is a UsageError.
    std::optional<std::string> option(std::string_view name);
    // When the current argument is exactly name, consumes it.
    bool flag(std::string_view name);
    // Consumes one of -D name=value (or -Dname=value), --curves=auto|exact|openscad,
    // --accel=sah|median|goldsmith-salmon|grid|nonuniform-grid|auto,
    // --polygon-method=watertight|snyder|marchal,
    // --diagnostics=text|json, --help/-h, or
    // the part (the first argument that is not an option). Returns false for anything else.
    bool common(CommonOptions& options);

private:
    std::span<const std::string> args_;
    size_t index_ = 0;
};

// "X,Y,Z" with finite numbers; what names the option in the error message.
csg::Vec3 parseVec3(std::string_view text, std::string_view what);
// "WxH" with positive integers up to 32768.
std::pair<int, int> parseSize(std::string_view text, std::string_view what);
// A positive integer up to maxValue.
int parsePositiveInt(std::string_view text, std::string_view what, int maxValue);
// A finite number from low to high (both included).
double parseNumberIn(std::string_view text, std::string_view what, double low, double high);

// Throws UsageError unless the part was given (and help was not asked for).
void requirePart(const CommonOptions& options, std::string_view command);

// The help text of the options every subcommand shares.
extern const char* const kCommonOptionsHelp;

}  // namespace viewer
