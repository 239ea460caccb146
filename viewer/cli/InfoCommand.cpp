#include "viewer/cli/InfoCommand.h"

#include <cstdio>

#include "io/TreeJson.h"
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

    io::TreeWriter tree(part.model);
    const io::NodeCounts counts = part.model.root ? tree.count(*part.model.root) : io::NodeCounts{};

    std::string out;
    csg::JsonWriter json(out);
    json.beginObject();
    json.key("part").value(options.part);
    json.key("curves").value(io::curveModeName(options.curves));
    // A 2-D part's tree is its shape shown 1 unit thick (io::Model::twoD).
    json.key("dimensions").value(part.model.twoD ? 2 : 3);
    io::writeCounts(json, counts);
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
