// Fitting a line's spans into LocalSpans::kCapacity: a primitive that may cross a line more
// often than that (a polygon mesh, a comb-shaped outline) keeps the first entry and the last
// exit and closes the narrowest gaps between consecutive spans, narrowest first (the first in
// t on a tie), until kCapacity remain. Nothing solid is dropped; the solid grows only by its
// thinnest voids along that one line.
#pragma once

#include <vector>

#include "primitives/LocalSpans.h"

namespace csg {

// Adds spans (ascending, disjoint) to out, closing gaps as above when there are too many.
void addWithinCapacity(const std::vector<LocalSpans::Entry>& spans, LocalSpans& out);

}  // namespace csg
