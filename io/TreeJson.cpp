#include "io/TreeJson.h"

namespace io {

void NodeCounts::addAll(const NodeCounts& o) {
    for (const auto& [name, n] : o.leaves) leaves[name] = add(leaves[name], n);
    unions = add(unions, o.unions);
    intersections = add(intersections, o.intersections);
    differences = add(differences, o.differences);
    transformed = add(transformed, o.transformed);
}

uint64_t NodeCounts::leafTotal() const {
    uint64_t total = 0;
    for (const auto& entry : leaves) total = add(total, entry.second);
    return total;
}

uint64_t NodeCounts::total() const {
    return add(leafTotal(), add(add(unions, intersections), differences));
}

void writeCounts(csg::JsonWriter& json, const NodeCounts& c) {
    json.key("counts").beginObject();
    json.key("nodes").value(c.total());
    // Every kind the language has appears, with 0 when unused, so readers need no defaults.
    std::map<std::string, uint64_t> leaves = c.leaves;
    for (const char* kind : csg::kPrimitiveNames) leaves[kind];
    json.key("leaves").beginObject().key("total").value(c.leafTotal());
    for (const auto& [name, n] : leaves) json.key(name).value(n);
    json.endObject();
    json.key("unions").value(c.unions);
    json.key("intersections").value(c.intersections);
    json.key("differences").value(c.differences);
    json.key("transformed").value(c.transformed);
    json.endObject();
}

NodeCounts TreeWriter::count(const csg::Node& node) {
    if (++uses_[&node] > 1) return counts_.at(&node);
    NodeCounts c;
    if (node.parentFromNode != csg::Mat4(1.0)) c.transformed = 1;
    switch (node.op) {
        case csg::Op::Leaf:
            c.leaves[csg::primitiveName(node.primitive)] = 1;
            break;
        case csg::Op::Union:
            c.unions = 1;
            break;
        case csg::Op::Intersection:
            c.intersections = 1;
            break;
        case csg::Op::Difference:
            c.differences = 1;
            break;
    }
    if (node.left) c.addAll(count(*node.left));
    if (node.right) c.addAll(count(*node.right));
    counts_[&node] = c;
    return c;
}

void TreeWriter::write(csg::JsonWriter& json, const csg::Node& node) {
    const bool shared = uses_[&node] > 1;
    if (shared) {
        if (auto it = ids_.find(&node); it != ids_.end()) {
            json.beginObject().key("ref").value(it->second).endObject();
            return;
        }
    }
    json.beginObject();
    if (shared) {
        const uint32_t id = uint32_t(ids_.size());
        ids_[&node] = id;
        json.key("id").value(id);
    }
    switch (node.op) {
        case csg::Op::Leaf:
            json.key("op").value(csg::primitiveName(node.primitive));
            csg::describePrimitive(json, node.primitive);
            break;
        case csg::Op::Union:
            json.key("op").value("union");
            break;
        case csg::Op::Intersection:
            json.key("op").value("intersection");
            break;
        case csg::Op::Difference:
            json.key("op").value("difference");
            break;
    }
    if (node.parentFromNode != csg::Mat4(1.0)) {
        json.key("transform").beginArray();
        for (int row = 0; row < 3; ++row) {
            json.beginArray();
            for (int col = 0; col < 4; ++col) json.value(node.parentFromNode[col][row]);
            json.endArray();
        }
        json.endArray();
    }
    if (node.tags.material != 0) json.key("material").value(node.tags.material);
    json.key("module").value(model_.modulePath(node.tags.source));
    json.key("source").value(model_.describeSource(node.tags.source));
    if (node.op != csg::Op::Leaf) {
        json.key("children").beginArray();
        if (node.left) write(json, *node.left);
        if (node.right) write(json, *node.right);
        json.endArray();
    }
    json.endObject();
}

}  // namespace io
