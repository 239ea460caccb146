// Grid planes through walls and gaps thinner than a cell.
//
// A grid edge whose line crosses the surface twice (out of one solid and into the next, or in
// and out of a thin wall) has the same sign at both ends, so dual contouring sees nothing there
// and fuses the gap or loses the wall. Adding one grid plane (a node coordinate on that axis)
// between the two crossings gives the edge a node of the other sign, on every line of the
// plane: the grid becomes rectilinear, finer only across thin features. Planes cost rays on the
// two other axes (one line per node of the plane), so they are placed sparingly: per axis, the
// fewest points that lie inside every thin interval (greedy by the intervals' upper ends, each
// new plane at the middle of the interval that needs it), then cast again, since lines of the
// new planes may reveal thin features of their own.
#pragma once

#include <cstdint>

#include "csg/Scene.h"
#include "csg/mesh/HermiteGrid.h"

namespace csg {

struct ThinPlanes {
    uint64_t added = 0;   // planes added over all rounds
    int rounds = 0;       // casts after the first
    bool capped = false;  // a round wanted more planes than its per-axis allowance
    // Edges of the final grid still crossed twice by facing surfaces: gaps narrower than
    // kThinMinWidth h, beyond the allowance, or met by no plane's lines. The mesh fuses them.
    uint64_t unresolved = 0;
};

// spec plus, per axis, planes stabbing every interval of grid.thinIntervals() at least
// minWidth wide; when that takes more than maxPerAxis new planes on an axis, the narrowest
// intervals there are left out (the width doubled until it fits) and *capped is set.
GridSpec withThinPlanes(const GridSpec& spec, const HermiteGrid& grid, double minWidth,
                        int maxPerAxis, uint64_t* added, bool* capped);

// Casts the uniform grid of spacing h over bounds, then adds planes through its thin walls and
// gaps and casts again, for up to three rounds, adding at most half of each axis's uniform node
// count in all. rays (when given) accumulates every cast's rays.
// distribute: as for HermiteGrid::cast.
HermiteGrid castResolvingThinFeatures(const Scene& scene, const Bounds3& bounds, double h,
                                      int threads, uint64_t* rays, ThinPlanes* planes,
                                      const ItemDistributor* distribute = nullptr);

}  // namespace csg
