// An evaluated part's "counts" and "tree" as JSON, as `csgray info` prints them. The tree is a
// DAG (a subtree may be shared by many parents), so counts are of the tree as written out
// (every use counts) while the walk visits each distinct node once, and the JSON prints a node
// used more than once in full at its first use, with an "id", and as {"ref": id} afterwards: a
// part that reuses a subtree 2^20 times stays small. The evaluator itself shares no nodes
// today; a caller building trees by hand may.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>

#include "csg/Tree.h"
#include "io/Model.h"
#include "primitives/base/Json.h"

namespace io {

// Counts of the expanded tree, saturating rather than wrapping for astronomically shared DAGs.
// Leaves are counted by primitive name, so a newly registered primitive needs no change here.
struct NodeCounts {
    std::map<std::string, uint64_t> leaves;
    uint64_t unions = 0, intersections = 0, differences = 0, transformed = 0;

    static uint64_t add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }
    void addAll(const NodeCounts& o);
    uint64_t leafTotal() const;
    uint64_t total() const;
};

// Writes "counts": nodes, leaves by primitive (every kind, 0 when unused), operators and
// transformed nodes.
void writeCounts(csg::JsonWriter& json, const NodeCounts& counts);

class TreeWriter {
public:
    explicit TreeWriter(const Model& model) : model_(model) {}

    // Counts of the subtree at node, memoized per distinct node; also counts each node's uses.
    // Call it on the root before write(), which needs the uses.
    NodeCounts count(const csg::Node& node);

    // The subtree at node as JSON: operators, primitives, transforms, module path and source.
    void write(csg::JsonWriter& json, const csg::Node& node);

private:
    const Model& model_;
    std::unordered_map<const csg::Node*, uint32_t> uses_;
    std::unordered_map<const csg::Node*, NodeCounts> counts_;
    std::unordered_map<const csg::Node*, uint32_t> ids_;
};

}  // namespace io
