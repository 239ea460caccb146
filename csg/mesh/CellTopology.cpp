#include "csg/mesh/CellTopology.h"

#include <cstddef>
#include <numeric>

using std::size_t;

namespace csg {

namespace {

inline int cornerOf(int a, int ob, int oc, int oa) {
    int off[3];
    off[a] = oa;
    off[(a + 1) % 3] = ob;
    off[(a + 2) % 3] = oc;
    return off[0] | (off[1] << 1) | (off[2] << 2);
}

// Endpoints of cell edge e.
inline void edgeCorners(int e, int& c0, int& c1) {
    const int a = e / 4, ob = e & 1, oc = (e >> 1) & 1;
    c0 = cornerOf(a, ob, oc, 0);
    c1 = cornerOf(a, ob, oc, 1);
}

int findRoot(std::array<int, 12>& parent, int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

CellCycles buildCycles(uint8_t mask) {
    auto inside = [mask](int c) { return ((mask >> c) & 1) != 0; };
    bool changes[12];
    for (int e = 0; e < 12; ++e) {
        int c0, c1;
        edgeCorners(e, c0, c1);
        changes[e] = inside(c0) != inside(c1);
    }

    // Step 1: pair the sign-changing edges on each of the 6 faces and join pairs into cycles.
    bool ambiguousFace = false;
    std::array<int, 12> parent;
    std::iota(parent.begin(), parent.end(), 0);
    for (int f = 0; f < 3; ++f) {
        for (int side = 0; side < 2; ++side) {
            const int u = (f + 1) % 3, v = (f + 2) % 3;
            std::array<bool, 4> corner;
            for (int dv = 0; dv < 2; ++dv)
                for (int du = 0; du < 2; ++du) {
                    int off[3];
                    off[f] = side;
                    off[u] = du;
                    off[v] = dv;
                    corner[size_t(du + 2 * dv)] = inside(off[0] | (off[1] << 1) | (off[2] << 2));
                }
            ambiguousFace = ambiguousFace || faceIsAmbiguous(corner);
            // Cell edge of a face edge: along u at v-offset o, or along v at u-offset o.
            auto cellEdge = [&](int axis, int o) {
                const int a = axis == 0 ? u : v;
                int off[3];
                off[f] = side;
                off[axis == 0 ? v : u] = o;
                off[a] = 0;
                return 4 * a + off[(a + 1) % 3] + 2 * off[(a + 2) % 3];
            };
            // Group the face's changing edges by segment and join each group.
            int first[2] = {-1, -1};
            for (int axis = 0; axis < 2; ++axis)
                for (int o = 0; o < 2; ++o) {
                    const int e = cellEdge(axis, o);
                    if (!changes[e]) continue;
                    const int s = faceSegment(corner, axis, o);
                    if (first[s] < 0)
                        first[s] = e;
                    else
                        parent[findRoot(parent, e)] = findRoot(parent, first[s]);
                }
        }
    }

    // Step 2: number the cycles.
    CellCycles cycles;
    cycles.ambiguousFace = ambiguousFace;
    cycles.edgeCycle.fill(-1);
    std::array<int8_t, 12> label;
    label.fill(-1);
    for (int e = 0; e < 12; ++e) {
        if (!changes[e]) continue;
        const int root = findRoot(parent, e);
        if (label[size_t(root)] < 0) label[size_t(root)] = int8_t(cycles.count++);
        cycles.edgeCycle[size_t(e)] = label[size_t(root)];
    }
    return cycles;
}

struct CycleTable {
    std::array<CellCycles, 256> entries;
    CycleTable() {
        for (int m = 0; m < 256; ++m) entries[size_t(m)] = buildCycles(uint8_t(m));
    }
};

}  // namespace

const CellCycles& cellCycles(uint8_t mask) {
    static const CycleTable table;
    return table.entries[mask];
}

bool faceIsAmbiguous(const std::array<bool, 4>& cornerInside) {
    return cornerInside[0] == cornerInside[3] && cornerInside[1] == cornerInside[2] &&
           cornerInside[0] != cornerInside[1];
}

int faceSegment(const std::array<bool, 4>& cornerInside, int edgeAxis, int edgeOffset) {
    if (!faceIsAmbiguous(cornerInside)) return 0;
    // The edge's inside endpoint: its du is the segment index (inside corners are diagonal, so
    // one has du = 0 and the other du = 1).
    if (edgeAxis == 1) return edgeOffset;  // along v at u-offset edgeOffset: du is fixed
    // Along u at v-offset o: endpoints (0, o) and (1, o); the inside one decides.
    return cornerInside[size_t(0 + 2 * edgeOffset)] ? 0 : 1;
}

}  // namespace csg
