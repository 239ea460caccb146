#include "viewer/cli/ProbeCommand.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>

#include "primitives/base/ParallelFor.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/cli/ProbeJson.h"
#include "viewer/cli/RayBatch.h"
#include "viewer/cli/dist/Ranks.h"

namespace viewer {

namespace {

const char* const kProbeHelp =
    "usage: csgray probe PART --origin X,Y,Z --dir X,Y,Z [options]\n"
    "       csgray probe PART --rays FILE [options]\n"
    "\n"
    "Casts rays through the part and prints every span where a ray is inside the solid, as\n"
    "JSON on stdout: {\"ray\": {...}, \"spans\": [{\"in\": END, \"out\": END}, ...]} with\n"
    "END = {\"t\", \"point\", \"normal\", \"object\"}. The direction is normalized, so t is a\n"
    "distance; spans are clipped to t >= 0 (a ray starting inside the solid begins with an\n"
    "\"in\" at t = 0 marked \"inside\": true). \"object\" names the primitive that bounds the\n"
    "span there: its module path and file:line:col.\n"
    "\n"
    "options:\n"
    "  --origin X,Y,Z         the ray's start\n"
    "  --dir X,Y,Z            the ray's direction (any non-zero length)\n"
    "  --rays FILE            many rays, one per line \"ox oy oz dx dy dz\" (- reads stdin);\n"
    "                         prints one JSON line per ray, in input order\n"
    "  --threads N            threads for --rays (default: all cores)\n"
    "\n"
    "Under mpirun or srun the --rays are spread over the ranks (each with --threads threads)\n"
    "and rank 0 prints every line in input order: the same output as one process.\n";

struct ProbeOptions {
    CommonOptions common;
    std::optional<csg::Vec3> origin, dir;
    std::optional<std::string> rays;
    int threads = 0;  // 0: all cores
};

ProbeOptions parseProbeOptions(std::span<const std::string> args) {
    ProbeOptions o;
    ArgCursor cursor(args);
    while (!cursor.done()) {
        if (auto v = cursor.option("--origin")) {
            o.origin = parseVec3(*v, "--origin");
        } else if (auto dir = cursor.option("--dir")) {
            o.dir = parseVec3(*dir, "--dir");
        } else if (auto rays = cursor.option("--rays")) {
            o.rays = *rays;
        } else if (auto threads = cursor.option("--threads")) {
            o.threads = parsePositiveInt(*threads, "--threads", 1024);
        } else if (cursor.flag("-")) {
            throw UsageError("the part cannot be read from stdin; give a file");
        } else if (!cursor.common(o.common)) {
            throw UsageError("probe: unknown option '" + cursor.peek() + "'");
        }
    }
    if (o.common.help) return o;
    requirePart(o.common, "probe");
    if (o.rays) {
        if (o.origin || o.dir) throw UsageError("probe: give either --rays or --origin/--dir");
    } else {
        if (!o.origin || !o.dir)
            throw UsageError("probe needs --origin X,Y,Z and --dir X,Y,Z (or --rays FILE)");
        if (!(glm::length(*o.dir) > 0.0) || !std::isfinite(glm::length(*o.dir)))
            throw UsageError("--dir must be a non-zero, finite direction");
    }
    return o;
}

// Under mpirun the rays are sharded over the ranks; only rank 0 opens the file (or reads stdin,
// which mpirun gives to rank 0 alone) and prints.
int probeRaysFromFile(const ProbeOptions& o, const ProbeJson& probe, Report& report,
                      const dist::Ranks& ranks) {
    const bool fromStdin = *o.rays == "-";
    std::FILE* input = nullptr;
    if (ranks.root()) {
        input = fromStdin ? stdin : std::fopen(o.rays->c_str(), "rb");
        if (!input)
            report.error(*o.rays,
                         std::string("cannot open the rays file: ") + std::strerror(errno));
    }
    if (!ranks.allOk(!ranks.root() || input)) return ranks.root() ? kExitIo : kExitOk;
    const int threads = csg::resolveThreads(o.threads);
    const std::string name = fromStdin ? "<stdin>" : *o.rays;
    const RayBatchResult result =
        ranks.mpi() ? probeRayBatchOnRanks(ranks, input, name, probe, threads, report)
                    : probeRayBatch(input, name, probe, threads, report);
    if (input && !fromStdin) std::fclose(input);
    return result.exitCode;
}

}  // namespace

int probeCommand(std::span<const std::string> args) {
    const ProbeOptions o = parseProbeOptions(args);
    if (o.common.help) {
        if (!dist::Ranks::job().root()) return kExitOk;  // under mpirun: once, by rank 0
        std::fputs(kProbeHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    Report report(o.common.jsonDiagnostics);
    LoadedPart part;
    const dist::Ranks& ranks = dist::Ranks::job();
    const int loaded = loadPart(o.common, report, part);
    if (!ranks.allOk(loaded == kExitOk)) return loaded != kExitOk ? loaded : kExitBadModel;

    const ProbeJson probe(part.model, part.scene);
    if (o.rays) return probeRaysFromFile(o, probe, report, ranks);
    if (!ranks.root()) return kExitOk;  // one ray: rank 0 answers it

    std::string out;
    csg::QueryContext ctx;
    probe.append(out, *o.origin, glm::normalize(*o.dir), ctx);
    out += '\n';
    if (!report.writeStdout(out)) return kExitIo;
    return kExitOk;
}

}  // namespace viewer
