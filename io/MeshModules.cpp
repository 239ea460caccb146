#include "io/MeshModules.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/BoundArgs.h"
#include "io/DataFiles.h"
#include "io/DxfModules.h"
#include "io/SvgModule.h"
#include "io/mesh/MeshFile.h"
#include "primitives/Polyhedron.h"

namespace io {

namespace {

constexpr const char* kPolyhedronForm =
    "polyhedron(points = [[x, y, z], ...], faces = [[i, j, k, ...], ...], convexity = 1)";
constexpr const char* kImportForm =
    "import(file = \"part.stl\" | \"part.off\" | \"part.obj\" | \"part.3mf\" | \"drawing.dxf\" | "
    "\"drawing.svg\", layer, convexity = 1, origin = [x, y], scale = 1, center = false, dpi = 72)";
// Out-of-range indices warned about one by one (as OpenSCAD does) before a summary.
constexpr uint64_t kMaxIndexWarnings = 10;

// The mesh as a leaf, or the empty solid with a warning when nothing of it has area; warnings
// at the call for a mesh that is not a closed, consistently wound manifold.
Instance meshLeaf(Evaluator& e, const InstantiationStmt& s, const GeomState& state,
                  std::vector<csg::Vec3> points, const csg::PolygonFaces& faces,
                  const std::string& what) {
    if (!s.children.empty()) e.warn(s.loc, s.name + "() takes no children; they are ignored");
    const csg::Polyhedron mesh = csg::Polyhedron::make(std::move(points), faces);
    if (mesh.invalidReason() == csg::Polyhedron::kNoFaces) {
        e.warn(s.loc, what + " has no faces of positive area; it is empty");
        return csg::NodePtr();
    }
    if (mesh.invalidReason()) e.fail(s.loc, what + ": " + mesh.invalidReason());
    const csg::MeshEdges& edges = mesh.edges();
    if (!edges.closed())
        e.warn(s.loc, what + " is not closed: " + std::to_string(edges.openEdges) + " of its " +
                          std::to_string(edges.edges) +
                          " edges belong to an odd number of faces (1: a boundary). csgray "
                          "takes the solid by crossing parity and drops the last crossing of a "
                          "line that has an odd count; OpenSCAD 2021 drops an open mesh from "
                          "booleans (\"The given mesh is not closed!\")");
    else if (edges.manyFaces > 0)
        e.warn(s.loc, what + " is not a manifold: " + std::to_string(edges.manyFaces) +
                          " edges belong to more than two faces. csgray takes the solid by "
                          "crossing parity");
    if (edges.closed() && edges.misoriented > 0)
        e.warn(s.loc, what + " has faces wound against their neighbours (" +
                          std::to_string(edges.misoriented) +
                          " edges). csgray takes the solid by crossing parity, which does not "
                          "depend on winding; OpenSCAD 2021 reports such a mesh as not closed "
                          "in booleans");
    return csg::leaf(mesh, {e.sourceTag(s.loc, e.childPath(state, s.name)), state.material});
}

// OpenSCAD's getVec3(x, y, z, 0): [x, y, z], or [x, y] with z = 0, of finite numbers.
std::optional<csg::Vec3> pointOf(const Value& v) {
    if (!v.isVector() || (v.list().size() != 3 && v.list().size() != 2)) return std::nullopt;
    csg::Vec3 p(0.0);
    for (size_t k = 0; k < v.list().size(); ++k) {
        const Value& x = v.list()[k];
        if (!x.isNumber() || !std::isfinite(x.number())) return std::nullopt;
        p[int(k)] = x.number();
    }
    return p;
}

}  // namespace

Instance polyhedronModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                          const GeomState& state) {
    const BoundArgs b =
        bindArgs(e, s, ctx, {"points", "faces", "convexity", "triangles"}, kPolyhedronForm);
    // points: finite [x, y, z] (or [x, y]); OpenSCAD 2021 stops there with an error too.
    if (!b.given(0)) e.fail(s.loc, "polyhedron() needs 'points'; expected " + std::string(b.form));
    if (!b[0].isVector()) b.bad(e, 0, "a list of points [x, y, z]");
    const ValueList& pointList = b[0].list();
    e.spend(b.loc(0), pointList.size());
    std::vector<csg::Vec3> points;
    points.reserve(pointList.size());
    for (size_t i = 0; i < pointList.size(); ++i) {
        const std::optional<csg::Vec3> p = pointOf(pointList[i]);
        if (!p)
            e.fail(b.loc(0), "polyhedron(): unable to convert points[" + std::to_string(i) +
                                 "] = " + pointList[i].brief() +
                                 " to a vec3 of finite numbers; expected " + std::string(b.form));
        points.push_back(*p);
    }
    // faces, or the deprecated triangles when faces is undefined (OpenSCAD 2021's rule).
    size_t facesArg = 1;
    if (!b.given(1) && b.given(3)) {
        facesArg = 3;
        e.warn(b.loc(3),
               "DEPRECATED: polyhedron(triangles=[]) will be removed in future releases. Use "
               "polyhedron(faces=[]) instead.");
    }
    if (!b.given(facesArg))
        e.fail(s.loc, "polyhedron() needs 'faces'; expected " + std::string(b.form));
    if (!b[facesArg].isVector()) b.bad(e, facesArg, "a list of faces [i, j, k, ...]");
    if (b.given(2) && !b[2].isNumber()) b.bad(e, 2, "a number (a preview hint, ignored)");
    const ValueList& faceList = b[facesArg].list();
    const std::string argName(b.names[facesArg]);
    csg::PolygonFaces faces;
    uint64_t outOfRange = 0;
    for (size_t f = 0; f < faceList.size(); ++f) {
        const Value& face = faceList[f];
        if (!face.isVector())
            b.bad(e, facesArg,
                  "a list of faces [i, j, k, ...] (" + argName + "[" + std::to_string(f) + "] is " +
                      face.brief() + ")");
        e.spend(b.loc(facesArg), face.list().size());
        const size_t before = faces.corners.size();
        for (size_t k = 0; k < face.list().size(); ++k) {
            const Value& index = face.list()[k];
            // OpenSCAD truncates the number to an index; a negative one wraps to a huge one.
            const double x = index.isNumber() ? std::trunc(index.number()) : -1.0;
            if (!index.isNumber() || !(x >= 0.0 && x < double(points.size()))) {
                if (++outOfRange <= kMaxIndexWarnings)
                    e.warn(b.loc(facesArg),
                           "Point index " + (index.isNumber() ? formatNumber(x) : index.brief()) +
                               " is out of bounds (from " + argName + "[" + std::to_string(f) +
                               "][" + std::to_string(k) + "]); it is skipped");
                continue;
            }
            faces.corners.push_back(static_cast<uint32_t>(x));
        }
        // Fewer than 3 corners left: no area (OpenSCAD keeps it, to no effect).
        if (faces.corners.size() - before < 3)
            faces.corners.resize(before);
        else
            faces.closeFace();
    }
    if (outOfRange > kMaxIndexWarnings)
        e.warn(b.loc(facesArg), "... " + std::to_string(outOfRange - kMaxIndexWarnings) +
                                    " more point indices out of bounds were skipped");
    return meshLeaf(e, s, state, std::move(points), faces, "polyhedron()");
}

Instance importModule(Evaluator& e, const InstantiationStmt& s, const ContextPtr& ctx,
                      const GeomState& state) {
    const BoundArgs b = bindArgs(
        e, s, ctx, {"file", "layer", "convexity", "origin", "scale", "center", "dpi"}, kImportForm);
    if (!b.given(0)) e.fail(s.loc, "import() needs a file; expected " + std::string(b.form));
    if (!b[0].isString()) b.bad(e, 0, "a file name");
    const bool dxf = isDxfFile(b[0].string()), svg = isSvgFile(b[0].string());
    // OpenSCAD 2021 reads layer, origin and scale for DXF only, center and dpi for SVG only.
    for (size_t i : {size_t(1), size_t(3), size_t(4), size_t(5), size_t(6)}) {
        const bool forDxf = i <= 4;
        if (b.given(i) && (forDxf ? !dxf : !svg))
            e.warn(b.loc(i), "import(): '" + std::string(b.names[i]) + "' applies to " +
                                 (forDxf ? "DXF" : "SVG") + " files only; ignored");
    }
    if (dxf) return importDxf(e, b, ctx, state);
    if (svg) return importSvg(e, b, state);
    const std::string& written = b[0].string();

    // The type by the lower-cased extension, as OpenSCAD decides it.
    const io::MeshFormat format = meshFormatOf(written);
    if (format != MeshFormat::Stl && format != MeshFormat::Off && format != MeshFormat::Obj &&
        format != MeshFormat::ThreeMf) {
        const std::string ext = lowerExtension(written);
        const bool openscadKnows =
            ext == ".amf" || ext == ".nef3" || ext == ".glb" || ext == ".gltf";
        e.fail(b.loc(0), "import(): " +
                             std::string(openscadKnows ? "importing " + ext +
                                                             " files is not supported by csgray"
                                                       : "unsupported file format") +
                             " ('" + written + "'); expected " + std::string(b.form));
    }
    if (!e.filesAllowed()) e.fail(b.loc(0), "import(): reading files is not allowed here");

    const std::filesystem::path path = lookupDataFile(e, s.loc, b.loc(0), written);
    PolygonMeshReadResult read = readPolygonMesh(path);
    if (!read.mesh) {
        std::string where = path.string();
        if (read.line > 0)
            where += ":" + std::to_string(read.line) + ":" + std::to_string(read.column);
        e.fail(b.loc(0), "import(): " + where + ": " + read.error);
    }
    return meshLeaf(e, s, state, std::move(read.mesh->positions), read.mesh->faces,
                    "import(\"" + written + "\")");
}

}  // namespace io
