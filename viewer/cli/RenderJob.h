// `csgray render` from parsed options to files: load and compile the part, frame the camera,
// derive the effects plan, render the tiles, write the image (and --stats) atomically. Ctrl-C
// at any point before the image is written stops the job with nothing written.
#pragma once

#include <span>
#include <string>

#include "viewer/cli/Cli.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/ImageOutput.h"

namespace viewer::render {

struct RenderJobOptions {
    CommonOptions common;
    std::string output;
    ImageFormat format = ImageFormat::Png;
    int width = 800, height = 600;
    int samplesPerAxis = 1;  // --aa
    int threads = 0;         // 0: all cores
    PlanSettings plan;
    std::string statsFile;  // --stats; empty: none
    bool quiet = false;
};

// Parses the arguments after "render" (throws UsageError).
RenderJobOptions parseRenderJobOptions(std::span<const std::string> args);

// The help text of `csgray render` (without the common options).
extern const char* const kRenderJobHelp;

// Runs the job; returns the exit code (kExitInterrupted after Ctrl-C).
int runRenderJob(const RenderJobOptions& options);

}  // namespace viewer::render
