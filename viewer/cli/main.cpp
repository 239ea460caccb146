// csgray: the command line. Dispatches to one subcommand per file (Probe, Info,
// RenderCommand); each parses its own options and returns the exit code of DESIGN.md.
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "viewer/cli/BenchCommand.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/CompareCommand.h"
#include "viewer/cli/ExportCommand.h"
#include "viewer/cli/InfoCommand.h"
#include "viewer/cli/ProbeCommand.h"
#include "viewer/cli/RenderCommand.h"
#include "viewer/cli/ViewCommand.h"

namespace {

const char* const kTopHelp =
    "usage: csgray COMMAND [ARGS]\n"
    "\n"
    "A CSG solid modeler that answers everything by casting rays. Parts are written in\n"
    "OpenSCAD's language (.scad; OpenSCAD's own .csg export loads too).\n"
    "\n"
    "commands:\n"
    "  probe    the spans of one ray or many rays through a part, as JSON\n"
    "  info     node counts, bounds and the evaluated CSG tree of a part, as JSON\n"
    "  render   a part to a PNG image\n"
    "  export   a part to a mesh (GLB, glTF, OBJ) within a distance tolerance\n"
    "  compare  a mesh against the part's exact surface: distances, volume, topology\n"
    "  view     an interactive window: progressive ray tracing, hot reload, click to probe\n"
    "  bench    accuracy: the root solvers' accuracy-versus-time report\n"
    "\n"
    "Run 'csgray COMMAND --help' for a command's options. stdout carries only the\n"
    "requested output; diagnostics go to stderr. Exit codes: 0 ok, 1 bad model or input,\n"
    "2 bad usage, 3 I/O error.\n";

int usageError(const std::string& message, std::string_view command) {
    std::fprintf(stderr, "csgray: error: %s\n", message.c_str());
    std::fprintf(stderr, "Try 'csgray %s--help'.\n",
                 command.empty() ? "" : (std::string(command) + " ").c_str());
    return viewer::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::fputs(kTopHelp, stderr);
        return viewer::kExitUsage;
    }
    const std::string& command = args[0];
    if (command == "--help" || command == "-h" || command == "help") {
        std::fputs(kTopHelp, stdout);
        return viewer::kExitOk;
    }
    const std::span<const std::string> rest(args.begin() + 1, args.end());
    try {
        if (command == "probe") return viewer::probeCommand(rest);
        if (command == "info") return viewer::infoCommand(rest);
        if (command == "render") return viewer::renderCommand(rest);
        if (command == "export") return viewer::exportCommand(rest);
        if (command == "compare") return viewer::compareCommand(rest);
        if (command == "view") return viewer::window::viewCommand(rest);
        if (command == "bench") return viewer::benchCommand(rest);
        return usageError("unknown command '" + command + "'", "");
    } catch (const viewer::UsageError& e) {
        return usageError(e.what(), command);
    } catch (const std::bad_alloc&) {
        std::fputs("csgray: error: out of memory\n", stderr);
        return viewer::kExitBadModel;
    } catch (const std::exception& e) {
        // Not expected: io/ reports problems as diagnostics and csg/ only throws CompileError.
        std::fprintf(stderr, "csgray: internal error: %s\n", e.what());
        return viewer::kExitBadModel;
    }
}
