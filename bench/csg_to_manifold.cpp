// Writes a part's CSG tree as JSON for bench/manifold/export.mjs, which rebuilds it with
// Manifold (OpenSCAD's current CSG engine): the same leaves, vertex for vertex, so the two
// exporters mesh the same polyhedron.
//   csg_to_manifold PART.scad [--curves auto|exact|openscad] [-D name=value ...] > tree.json
// Nodes: {"op": "union" | "intersection" | "difference", "a": node, "b": node};
// {"extrude": {"contours": [[x, y, ...], ...], "rule": "NonZero", "height": h, "scale": [sx,
// sy]}, "m": [16 numbers, column-major]} for an untwisted linear_extrude of a straight-edged
// outline (its region's outer contours counter-clockwise, their holes clockwise); {"hull": [x, y,
// z, ...]} for a convex leaf (a box, OpenSCAD's faceted cylinder or sphere: the convex hull of its
// world vertices is the leaf);
// {"mesh": {"v": [x, y, z, ...], "t": [i, j, k, ...]}} for a polyhedron or an imported mesh;
// {"empty": true} for the empty solid. A leaf with
// curved faces (an exact sphere, torus, ...) is refused: Manifold has only polyhedra, so such a
// part is compared under --curves openscad; the refusal names the leaf's kind, so that
// bench/peer_export.sh can say why a part has no Manifold row. -D overrides a top-level
// variable as csgray's -D does (the faceting sweeps of bench/peer_export.sh set $fn, $fa, $fs).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "csg/Tree.h"
#include "csg/derived/Flatten2D.h"
#include "io/Diagnostic.h"
#include "io/Evaluate.h"
#include "io/ExtrusionMesh.h"
#include "io/Faceting.h"
#include "primitives/Box.h"
#include "primitives/ConvexPolytope.h"
#include "primitives/Extrusion.h"
#include "primitives/HalfSpace.h"
#include "primitives/Polyhedron.h"
#include "primitives/Primitives.h"

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

// An untwisted linear_extrude of a straight-edged outline as Manifold's extrude: the
// outline's region as io::chordRegion chains and unites it (outer contours counter-clockwise,
// holes clockwise, the region by either fill rule), height and top scale, and the matrix
// (column-major) that puts its bottom at z0. False with a reason for an outline with curved
// segments or one that does not chain into closed contours.
bool extrusion(const csg::Extrusion& e, const csg::Mat4& m, std::string& out, std::string& why) {
    if (!csg::straightEdged(*e.outline)) {
        why = "leaf 'extrusion' has curved faces (an outline with arcs or Beziers)";
        return false;
    }
    // Lines take no chords: any deviation gives the outline's own corners.
    const std::optional<std::vector<io::RegionPolygon>> region =
        io::chordRegion(*e.outline, e.box, 1.0);
    if (!region) {
        why = "leaf 'extrusion': its outline does not chain into closed contours";
        return false;
    }
    out += "{\"extrude\":{\"contours\":[";
    bool firstContour = true;
    const auto contour = [&](const std::vector<csg::Vec2>& points) {
        out += firstContour ? "[" : ",[";
        firstContour = false;
        for (size_t k = 0; k < points.size(); ++k) {
            if (k) out += ',';
            number(out, points[k].x);
            out += ',';
            number(out, points[k].y);
        }
        out += ']';
    };
    for (const io::RegionPolygon& polygon : *region) {
        contour(polygon.outer);
        for (const std::vector<csg::Vec2>& hole : polygon.holes) contour(hole);
    }
    out += "],\"rule\":\"NonZero\",\"height\":";
    number(out, e.z1 - e.z0);
    out += ",\"scale\":[";
    number(out, e.scale.x);
    out += ',';
    number(out, e.scale.y);
    out += "]},\"m\":[";
    const csg::Mat4 placed = m * glm::translate(csg::Mat4(1.0), csg::Vec3(0.0, 0.0, e.z0));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            if (c || r) out += ',';
            number(out, placed[c][r]);
        }
    out += "]}";
    return true;
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
    if (const auto* e = std::get_if<csg::Extrusion>(&p);
        e && e->outline && e->kind == csg::Extrusion::Kind::Linear && !e->twisted &&
        std::isfinite(e->z0) && std::isfinite(e->z1))
        return extrusion(*e, m, out, why);
    why = std::string("leaf '") + csg::primitiveName(p) + "' ";
    if (const auto* extrusion = std::get_if<csg::Extrusion>(&p))
        why += extrusion->kind == csg::Extrusion::Kind::Plane ? "is a 2-D shape (no solid)"
               : extrusion->kind == csg::Extrusion::Kind::Linear
                   ? "is a twisted linear_extrude, exact (--curves openscad makes it OpenSCAD's "
                     "sliced polyhedron)"
                   : "has curved faces (a rotate_extrude, exact)";
    else if (std::holds_alternative<csg::HalfSpace>(p))
        why += "is an unbounded half-space (Manifold takes bounded solids)";
    else
        why += "has curved faces (Manifold takes polyhedra: try --curves openscad)";
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    const char* usage =
        "usage: csg_to_manifold PART.scad [--curves auto|exact|openscad] [-D name=value ...]\n";
    if (argc < 2) {
        std::fputs(usage, stderr);
        return 2;
    }
    io::EvaluateOptions options;
    for (int i = 2; i < argc; i += 2) {
        const std::string arg = argv[i];
        if (i + 1 >= argc) {
            std::fputs(usage, stderr);
            return 2;
        }
        if (arg == "--curves") {
            const auto mode = io::parseCurveMode(argv[i + 1]);
            if (!mode) {
                std::fprintf(stderr, "csg_to_manifold: unknown --curves %s\n", argv[i + 1]);
                return 2;
            }
            options.curves = *mode;
        } else if (arg == "-D") {
            const std::string define = argv[i + 1];
            const size_t eq = define.find('=');
            if (eq == std::string::npos || eq == 0) {
                std::fprintf(stderr, "csg_to_manifold: -D wants name=value, not %s\n", argv[i + 1]);
                return 2;
            }
            options.defines.emplace_back(define.substr(0, eq), define.substr(eq + 1));
        } else {
            std::fputs(usage, stderr);
            return 2;
        }
    }
    const io::EvaluateResult result = io::evaluateFile(argv[1], options);
    if (!result.ok()) {
        // The evaluator's errors first, so that the last line says why.
        for (const io::Diagnostic& d : result.diagnostics)
            std::fprintf(stderr, "%s\n", io::formatDiagnostic(d).c_str());
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
