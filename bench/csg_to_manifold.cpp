// Writes a part's CSG tree as JSON for bench/manifold/export.mjs, which rebuilds it with
// Manifold (OpenSCAD's current CSG engine): the same leaves, vertex for vertex, so the two
// exporters mesh the same polyhedron.
//   csg_to_manifold PART.scad [--curves auto|exact|openscad] > tree.json
// Nodes: {"op": "union" | "intersection" | "difference", "a": node, "b": node};
// {"hull": [x, y, z, ...]} for a convex leaf (a box, OpenSCAD's faceted cylinder or sphere: the
// convex hull of its world vertices is the leaf); {"mesh": {"v": [x, y, z, ...], "t": [i, j, k,
// ...]}} for a polyhedron or an imported mesh; {"empty": true} for the empty solid. A leaf with
// curved faces (an exact sphere, torus, ...) is refused: Manifold has only polyhedra, so such a
// part is compared under --curves openscad.
#include <charconv>
#include <cstdio>
#include <string>

#include "csg/Tree.h"
#include "io/Evaluate.h"
#include "io/Faceting.h"
#include "primitives/Box.h"
#include "primitives/ConvexPolytope.h"
#include "primitives/Polyhedron.h"

namespace {

void number(std::string& out, double v) {
    char buffer[32];
    out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

void points(std::string& out, const csg::Mat4& m, const std::vector<csg::Vec3>& local) {
    out += '[';
    for (size_t i = 0; i < local.size(); ++i) {
        const csg::Vec3 p = csg::Vec3(m * glm::dvec4(local[i], 1.0));
        for (int k = 0; k < 3; ++k) {
            if (i || k) out += ',';
            number(out, p[k]);
        }
    }
    out += ']';
}

// False with a reason when a leaf is not a polyhedron.
bool write(const csg::NodePtr& node, const csg::Mat4& parent, std::string& out, std::string& why) {
    if (!node) {
        out += "{\"empty\":true}";
        return true;
    }
    const csg::Mat4 m = parent * node->parentFromNode;
    if (node->op != csg::Op::Leaf) {
        const char* op = node->op == csg::Op::Union          ? "union"
                         : node->op == csg::Op::Intersection ? "intersection"
                                                             : "difference";
        out += std::string("{\"op\":\"") + op + "\",\"a\":";
        if (!write(node->left, m, out, why)) return false;
        out += ",\"b\":";
        if (!write(node->right, m, out, why)) return false;
        out += '}';
        return true;
    }
    const csg::Primitive& p = node->primitive;
    if (const auto* box = std::get_if<csg::Box>(&p)) {
        std::vector<csg::Vec3> corners;
        for (int k = 0; k < 8; ++k)
            corners.push_back({k & 1 ? box->hi.x : box->lo.x, k & 2 ? box->hi.y : box->lo.y,
                               k & 4 ? box->hi.z : box->lo.z});
        out += "{\"hull\":";
        points(out, m, corners);
        out += '}';
        return true;
    }
    if (const auto* poly = std::get_if<csg::ConvexPolytope>(&p); poly && poly->data) {
        out += "{\"hull\":";
        points(out, m, poly->data->vertices);
        out += '}';
        return true;
    }
    if (const auto* mesh = std::get_if<csg::Polyhedron>(&p); mesh && mesh->data) {
        out += "{\"mesh\":{\"v\":";
        points(out, m, mesh->data->vertices);
        out += ",\"t\":[";
        // A mirroring transform turns the triangles inside out: reverse them.
        const bool mirrored = glm::determinant(csg::Mat3(m)) < 0.0;
        for (size_t t = 0; t < mesh->data->triangles.size(); ++t) {
            const auto& tri = mesh->data->triangles[t];
            const uint32_t order[3] = {tri[0], mirrored ? tri[2] : tri[1],
                                       mirrored ? tri[1] : tri[2]};
            for (int k = 0; k < 3; ++k) {
                if (t || k) out += ',';
                out += std::to_string(order[k]);
            }
        }
        out += "]}}";
        return true;
    }
    why = "a leaf has curved faces (Manifold takes polyhedra: try --curves openscad)";
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: csg_to_manifold PART.scad [--curves auto|exact|openscad]\n");
        return 2;
    }
    io::EvaluateOptions options;
    for (int i = 2; i + 1 < argc; i += 2)
        if (std::string(argv[i]) == "--curves") {
            const auto mode = io::parseCurveMode(argv[i + 1]);
            if (!mode) {
                std::fprintf(stderr, "csg_to_manifold: unknown --curves %s\n", argv[i + 1]);
                return 2;
            }
            options.curves = *mode;
        }
    const io::EvaluateResult result = io::evaluateFile(argv[1], options);
    if (!result.ok()) {
        std::fprintf(stderr, "csg_to_manifold: %s does not evaluate\n", argv[1]);
        return 1;
    }
    std::string out, why;
    if (!write(result.model->root, csg::Mat4(1.0), out, why)) {
        std::fprintf(stderr, "csg_to_manifold: %s: %s\n", argv[1], why.c_str());
        return 1;
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    std::fputc('\n', stdout);
    return 0;
}
