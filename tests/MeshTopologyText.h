// Test helper: a MeshTopology's defect counts as one line, for the message of a failed
// closedManifold() assertion.
#pragma once

#include <string>

#include "csg/mesh/MeshCheck.h"

namespace csg {

inline std::string describe(const MeshTopology& t) {
    return "boundary " + std::to_string(t.boundaryEdges) + " nonmanifold " +
           std::to_string(t.nonManifoldEdges) + " misoriented " +
           std::to_string(t.misorientedEdges) + " vertices " +
           std::to_string(t.nonManifoldVertices) + " degenerate " +
           std::to_string(t.degenerateTriangles);
}

}  // namespace csg
