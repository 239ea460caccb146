// A quick look at a part until the Whitted renderer (issue 4) lands: one primary ray per pixel,
// the material's color lit by a headlight (Lambert, light at the eye), no shadows or
// reflections. The camera is the model's, or one that frames the part's finite bounds.
#pragma once

#include "csg/Scene.h"
#include "io/Model.h"
#include "io/PngWriter.h"

namespace viewer {

// The background when the model sets none: OpenSCAD's default light cream.
inline constexpr csg::Vec3 kDefaultBackground{1.0, 1.0, 0.898};

// A camera looking at the hull of the scene's bounded leaves from OpenSCAD's default
// direction (front-right, above), far enough that the whole hull fits an image of the given
// aspect (width / height). Scenes with no bounded leaf get io::Camera{}.
io::Camera frameBounds(const csg::Scene& scene, double aspect);

// Renders width x height pixels, rows spread over threads (>= 1).
io::Rgb8Image renderPreview(const io::Model& model, const csg::Scene& scene, int width, int height,
                            int threads);

}  // namespace viewer
