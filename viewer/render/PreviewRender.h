// `csgray render --preview`: a quick look at a part, one primary ray per pixel, the material's
// colour lit by a headlight (Lambert, light at the eye), no shadows or secondary rays. It uses
// the renderer's camera (the model's, or one framing the part) and colour conversions.
#pragma once

#include "csg/Scene.h"
#include "viewer/render/Look.h"
#include "viewer/render/PngWriter.h"

namespace viewer::render {

// Renders width x height pixels, rows spread over threads (>= 1).
Rgb8Image renderPreview(const SceneLook& look, const csg::Scene& scene, int width, int height,
                        int threads);

}  // namespace viewer::render
