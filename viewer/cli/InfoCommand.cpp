// The tree is a DAG (a subtree may be shared by many parents), so counts are of the tree as
// written out (every use counts) while the walk visits each distinct node once, and the JSON
// prints a node used more than once in full at its first use, with an "id", and as
// {"ref": id} afterwards: a part that reuses a subtree 2^20 times stays small.
#include "viewer/cli/InfoCommand.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <unordered_map>

#include "primitives/base/Json.h"
#include "viewer/cli/Cli.h"
#include "viewer/cli/LoadPart.h"
#include "viewer/render/EffectsPlan.h"
#include "viewer/render/RenderCamera.h"

namespace viewer {

namespace {

const char* const kInfoHelp =
    "usage: csgray info PART [options]\n"
    "\n"
    "Prints JSON on stdout: the \"curves\" mode the part was read with (--curves), its\n"
    "\"dimensions\" (2 for a 2-D part, whose tree is its shape 1 unit thick as OpenSCAD\n"
    "previews it; else 3), \"counts\" of the evaluated tree's nodes by kind (leaves by\n"
    "primitive, unions, intersections, differences, transformed nodes), world \"bounds\"\n"
    "(null when empty; an unbounded side is null), the compiled leaf count, the scene extras\n"
    "(camera, lights, background, materials)\n"
    "and the \"tree\": operators, primitives with their parameters in local coordinates (a\n"
    "faceted cylinder or sphere is a convex_polyhedron with its fragments, rings and planes),\n"
    "transforms (3x4 rows, parent from node) and\n"
    "each node's module path and file:line:col. A subtree used more than once is printed\n"
    "once with an \"id\" and referenced as {\"ref\": id}. Last, the renderer's effects\n"
    "\"plan\" with render's defaults: which lights get shadow rays and why, and which\n"
    "materials reflect, refract or take direct light.\n"
    "\n"
    "options:\n";

// Counts of the expanded tree, saturating rather than wrapping for astronomically shared DAGs.
// Leaves are counted by primitive name, so a newly registered primitive needs no change here.
struct NodeCounts {
    std::map<std::string, uint64_t> leaves;
    uint64_t unions = 0, intersections = 0, differences = 0, transformed = 0;

    static uint64_t add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }
    void addAll(const NodeCounts& o) {
        for (const auto& [name, n] : o.leaves) leaves[name] = add(leaves[name], n);
        unions = add(unions, o.unions);
        intersections = add(intersections, o.intersections);
        differences = add(differences, o.differences);
        transformed = add(transformed, o.transformed);
    }
    uint64_t leafTotal() const {
        uint64_t total = 0;
        for (const auto& entry : leaves) total = add(total, entry.second);
        return total;
    }
    uint64_t total() const {
        return add(leafTotal(), add(add(unions, intersections), differences));
    }
};

class TreeWriter {
public:
    explicit TreeWriter(const io::Model& model) : model_(model) {}

    // Counts of the subtree at node, memoized per distinct node; also counts each node's uses.
    NodeCounts count(const csg::Node& node) {
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

    void write(csg::JsonWriter& json, const csg::Node& node) {
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
                writePrimitive(json, node.primitive);
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

private:
    static void writePrimitive(csg::JsonWriter& json, const csg::Primitive& primitive) {
        json.key("op").value(csg::primitiveName(primitive));
        csg::describePrimitive(json, primitive);
    }

    const io::Model& model_;
    std::unordered_map<const csg::Node*, uint32_t> uses_;
    std::unordered_map<const csg::Node*, NodeCounts> counts_;
    std::unordered_map<const csg::Node*, uint32_t> ids_;
};

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

void writeBounds(csg::JsonWriter& json, const csg::Bounds3& b) {
    json.key("bounds");
    if (b.empty()) {
        json.null();
        return;
    }
    json.beginObject().key("min").vec(b.lo, 3).key("max").vec(b.hi, 3).endObject();
}

void writeExtras(csg::JsonWriter& json, const io::Model& model) {
    json.key("camera");
    if (model.camera) {
        const render::Camera& c = *model.camera;
        json.beginObject()
            .key("eye")
            .vec(c.eye, 3)
            .key("center")
            .vec(c.center, 3)
            .key("up")
            .vec(c.up, 3)
            .key("fov")
            .value(c.fov)
            .key("projection")
            .value(c.projection == render::Projection::Perspective ? "perspective" : "orthographic")
            .endObject();
    } else {
        json.null();
    }
    json.key("lights").beginArray();
    for (const render::Light& l : model.lights)
        json.beginObject()
            .key("position")
            .vec(l.position, 3)
            .key("color")
            .vec(l.color, 3)
            .key("intensity")
            .value(l.intensity)
            .key("shadows")
            .value(l.shadows)
            .endObject();
    json.endArray();
    json.key("background");
    if (model.background) {
        json.vec(*model.background, 3);
    } else {
        json.null();
    }
    json.key("materials").beginArray();
    for (const render::Material& m : model.materials)
        json.beginObject()
            .key("color")
            .vec(m.color, 4)
            .key("ambient")
            .value(m.ambient)
            .key("diffuse")
            .value(m.diffuse)
            .key("specular")
            .value(m.specular)
            .key("shininess")
            .value(m.shininess)
            .key("reflect")
            .value(m.reflect)
            .key("transmit")
            .value(m.transmit)
            .key("ior")
            .value(m.ior)
            .endObject();
    json.endArray();
    json.key("highlighted").value(uint64_t(model.highlighted.size()));
    json.key("backgroundParts").value(uint64_t(model.backgroundParts.size()));
}

}  // namespace

int infoCommand(std::span<const std::string> args) {
    CommonOptions options;
    ArgCursor cursor(args);
    while (!cursor.done())
        if (!cursor.common(options))
            throw UsageError("info: unknown option '" + cursor.peek() + "'");
    if (options.help) {
        std::fputs(kInfoHelp, stdout);
        std::fputs(kCommonOptionsHelp, stdout);
        return kExitOk;
    }
    requirePart(options, "info");

    Report report(options.jsonDiagnostics);
    LoadedPart part;
    if (const int code = loadPart(options, report, part); code != kExitOk) return code;

    TreeWriter tree(part.model);
    const NodeCounts counts = part.model.root ? tree.count(*part.model.root) : NodeCounts{};

    std::string out;
    csg::JsonWriter json(out);
    json.beginObject();
    json.key("part").value(options.part);
    json.key("curves").value(io::curveModeName(options.curves));
    // A 2-D part's tree is its shape shown 1 unit thick (io::Model::twoD).
    json.key("dimensions").value(part.model.twoD ? 2 : 3);
    writeCounts(json, counts);
    writeBounds(json, part.scene.bounds());
    json.key("compiledLeaves").value(uint64_t(part.scene.leafCount()));
    writeExtras(json, part.model);
    json.key("tree");
    if (part.model.root) {
        tree.write(json, *part.model.root);
    } else {
        json.null();
    }
    // The renderer's effects plan with render's default settings (a square image frames the
    // default camera, which only places the default light).
    json.key("plan");
    const render::Camera camera =
        part.model.camera ? *part.model.camera : render::frameBounds(part.scene, 1.0);
    render::writeEffectsPlan(
        json, render::makeEffectsPlan(part.model, part.model.root.get(), part.scene, camera, {}));
    json.endObject();
    out += '\n';
    if (!report.writeStdout(out)) return kExitIo;
    return kExitOk;
}

}  // namespace viewer
