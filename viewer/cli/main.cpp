// csgray: the command line. kCommands names every subcommand (one per file, XCommand.cpp) and
// dispatches to it; each parses its own options and returns the exit code of DESIGN.md.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <span>
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
#include "viewer/cli/Report.h"
#include "viewer/cli/ViewCommand.h"
#include "viewer/cli/dist/Ranks.h"

namespace {

// Every command, in the order `csgray --help` lists them: the help and the dispatch both come
// from this table, so a command cannot be listed without being run, or the reverse.
struct Command {
    std::string_view name;
    std::string_view summary;                       // one line of `csgray --help`
    int (*run)(std::span<const std::string> args);  // args after the name; returns the exit code
    bool distributed = false;  // under mpirun every rank runs it; else rank 0 alone does
};

constexpr Command kCommands[] = {
    {"probe", "the spans of one ray or many rays through a part, as JSON", viewer::probeCommand,
     true},
    {"info", "node counts, bounds and the evaluated CSG tree of a part, as JSON",
     viewer::infoCommand},
    {"render", "a part to a PNG image", viewer::renderCommand, true},
    {"export", "a part to a mesh (GLB, glTF, OBJ, STL, 3MF) within a distance tolerance",
     viewer::exportCommand, true},
    {"compare", "a mesh against the part's exact surface: distances, volume, topology",
     viewer::compareCommand},
    {"view", "an interactive window: progressive ray tracing, hot reload, click to probe",
     viewer::window::viewCommand},
    {"bench", "accuracy: the root solvers' accuracy-versus-time report", viewer::benchCommand},
};

std::string topHelp() {
    std::string help =
        "usage: csgray COMMAND [ARGS]\n"
        "\n"
        "A CSG solid modeler that answers everything by casting rays. Parts are written in\n"
        "OpenSCAD's language (.scad; OpenSCAD's own .csg export loads too).\n"
        "\n"
        "commands:\n";
    size_t width = 0;
    for (const Command& c : kCommands) width = std::max(width, c.name.size());
    for (const Command& c : kCommands) {
        help += "  ";
        help += c.name;
        help.append(width - c.name.size() + 2, ' ');
        help += c.summary;
        help += '\n';
    }
    help +=
        "\n"
        "Run 'csgray COMMAND --help' for a command's options. stdout carries only the\n"
        "requested output; diagnostics go to stderr. Exit codes: 0 ok, 1 bad model or input,\n"
        "2 bad usage, 3 I/O error.\n";
    return help;
}

int usageError(const std::string& message, std::string_view command) {
    std::fprintf(stderr, "csgray: error: %s\n", message.c_str());
    std::fprintf(stderr, "Try 'csgray %s--help'.\n",
                 command.empty() ? "" : (std::string(command) + " ").c_str());
    return viewer::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
    // MPI starts here, before any thread, when mpirun or srun started this process.
    const viewer::dist::Ranks& ranks = viewer::dist::Ranks::job();
    if (!ranks.root()) viewer::Report::showErrorsOnly();
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::fputs(topHelp().c_str(), stderr);
        return viewer::kExitUsage;
    }
    const std::string& command = args[0];
    if (command == "--help" || command == "-h" || command == "help") {
        std::fputs(topHelp().c_str(), stdout);
        return viewer::kExitOk;
    }
    const std::span<const std::string> rest(args.begin() + 1, args.end());
    try {
        for (const Command& c : kCommands) {
            if (c.name != command) continue;
            // A command that does not spread its work (export, info, ...) runs once per job.
            if (!c.distributed && !ranks.root()) return viewer::kExitOk;
            return c.run(rest);
        }
        return usageError("unknown command '" + command + "'", "");
    } catch (const viewer::UsageError& e) {
        if (!ranks.root()) return viewer::kExitUsage;  // every rank sees it; rank 0 says it
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
