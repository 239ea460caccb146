// Volume of a compiled scene by integrating span lengths over a grid of parallel rays.
#pragma once

#include "csg/Scene.h"

namespace csg {

// The axis volume()'s lines run along (the values index a Vec3).
enum class VolumeAxis : int { X = 0, Y = 1, Z = 2, Auto = -1 };

// Casts resolution x resolution rays along the axis (Auto: volumeLineAxis's) through the
// centres of a grid of cells covering the scene's bounds across it and sums span length times
// cell area. Exact along each ray, so the only error is the 2-D quadrature across the
// silhouette (relative error ~ resolution^-1.5 for smooth parts). Returns NaN-free 0 for an
// empty scene and +inf for an unbounded one. Rows run on `threads` threads (0: one per core)
// and the result does not depend on how many.
double volume(const Scene& scene, int resolution, int threads = 0,
              VolumeAxis axis = VolumeAxis::Auto);

// z, unless the part's twisted extrusions lie less along another axis. A line's solve through a
// twisted extrusion grows with the twist it sweeps (Debian's example020, a spring of 1 500
// degrees, took 124 s of compare's volume along its axis; bench/README.md), while a line across
// the axis meets a single section. The price: a twisted part's silhouette across its axis has
// many more edges than along it, so the quadrature error grows (on example020 at 1024 lines a
// side, ~2e-4 of the volume along x against ~1e-5 along y or z).
VolumeAxis volumeLineAxis(const Scene& scene);

}  // namespace csg
