// Volume of a compiled scene by integrating span lengths over a grid of parallel rays.
#pragma once

#include "csg/Scene.h"

namespace csg {

// Casts resolution x resolution rays along +z through the centres of a grid of cells covering
// the scene's x-y bounds and sums span length times cell area. Exact along each ray, so the
// only error is the 2-D quadrature across the silhouette (relative error ~ resolution^-1.5 for
// smooth parts). Returns NaN-free 0 for an empty scene and +inf for an unbounded one. Rows run
// on `threads` threads (0: one per core) and the result does not depend on how many.
double volume(const Scene& scene, int resolution, int threads = 0);

}  // namespace csg
