// The exact boundary of all-polyhedral parts (csg/mesh/PolyhedralBoundary.h), the export's
// default for them. Oracles independent of the code: volumes by hand (a notched cube, two
// overlapping boxes, a cube bored by OpenSCAD's 16-gon), the invariance of volume under a turn,
// and OpenSCAD 2021's own STL of the peer part (the same polyhedron: the same volume, and no
// more triangles than OpenSCAD writes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>

#include "csg/Scene.h"
#include "csg/Volume.h"
#include "csg/mesh/MeshCheck.h"
#include "csg/mesh/PolyhedralBoundary.h"
#include "csg/mesh/Tessellate.h"
#include "io/ChordFaceting.h"
#include "io/Evaluate.h"
#include "io/mesh/MeshFile.h"
#include "tests/MissingTool.h"
#include "tests/PartHelpers.h"
#include "tests/TempDir.h"

namespace {

using csg::testing::compiled;

using csg::TriangleMesh;

// The exact boundary, checked closed, outward and free of self-intersections.
TriangleMesh exactMesh(const csg::Scene& scene) {
    csg::PolyhedralBoundaryStats stats;
    const auto mesh = csg::polyhedralBoundary(scene, 0, &stats);
    EXPECT_TRUE(mesh.has_value()) << (stats.declined ? stats.declined : "");
    if (!mesh) return {};
    const csg::MeshTopology topology = csg::checkTopology(*mesh);
    EXPECT_TRUE(topology.closedManifold())
        << topology.boundaryEdges << " boundary, " << topology.nonManifoldEdges << " non-manifold, "
        << topology.misorientedEdges << " misoriented edges";
    EXPECT_EQ(csg::findSelfIntersections(*mesh).pairs, 0u);
    return *mesh;
}

TEST(ExactMesh, NotchedCubeByHand) {
    // A unit cube cut from the corner of a 2-cube: 8 - 1; 9 faces, the notch's three concave.
    const TriangleMesh mesh =
        exactMesh(compiled("difference() { cube(2, center=true); cube(1); }"));
    EXPECT_NEAR(csg::signedVolume(mesh), 7.0, 1e-12);
    // 3 whole faces (2 triangles each), 3 L-shaped faces (4 each), the notch's 3 squares (2
    // each): 24 at the fewest.
    EXPECT_LE(mesh.triangles.size(), 30u);
}

TEST(ExactMesh, OverlappingBoxesUnionByHand) {
    // Unit cubes at the origin and at (0.5, 0.3, 0.2): 1 + 1 - 0.5 * 0.7 * 0.8 = 1.72.
    const TriangleMesh mesh = exactMesh(compiled("cube(1); translate([0.5, 0.3, 0.2]) cube(1);"));
    EXPECT_NEAR(csg::signedVolume(mesh), 1.72, 1e-12);
}

TEST(ExactMesh, CubeBoredByOpenScadsPolygonByHand) {
    // OpenSCAD's 16-gon of radius 0.3 has area 16/2 r^2 sin(2 pi / 16); the bore runs through.
    const TriangleMesh mesh = exactMesh(compiled(
        "difference() { cube(1, center=true); cylinder(h=2, r=0.3, center=true, $fn=16); }"));
    const double bore = 8.0 * 0.09 * std::sin(std::numbers::pi / 8.0);
    EXPECT_NEAR(csg::signedVolume(mesh), 1.0 - bore, 1e-12);
    // OpenSCAD's own mesh of it: 32 triangles in the bore, 20 in each cap around the hole, 2 on
    // each of the 4 sides: 80.
    EXPECT_LE(mesh.triangles.size(), 80u);
}

// A polyhedron() of 2 * 6 * squares^2 triangles: the cube of side 2 about the origin, each face
// a grid of squares x squares.
std::string finelyDividedCube(int squares) {
    std::string points, faces;
    int next = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int first = next;
            for (int i = 0; i <= squares; ++i)
                for (int j = 0; j <= squares; ++j, ++next) {
                    double p[3];
                    p[axis] = side ? 1.0 : -1.0;
                    p[(axis + 1) % 3] = -1.0 + 2.0 * i / squares;
                    p[(axis + 2) % 3] = -1.0 + 2.0 * j / squares;
                    points += (next ? ",[" : "[") + std::to_string(p[0]) + "," +
                              std::to_string(p[1]) + "," + std::to_string(p[2]) + "]";
                }
            const auto at = [&](int i, int j) {
                return std::to_string(first + i * (squares + 1) + j);
            };
            for (int i = 0; i < squares; ++i)
                for (int j = 0; j < squares; ++j) {
                    // Outward on the high side; the low side runs the other way round.
                    const std::string a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1),
                                      d = at(i, j + 1);
                    faces += std::string(faces.empty() ? "" : ",") +
                             (side ? "[" + a + "," + b + "," + c + "],[" + a + "," + c + "," + d
                                   : "[" + a + "," + c + "," + b + "],[" + a + "," + d + "," + c) +
                             "]";
                }
        }
    return "polyhedron(points=[" + points + "], faces=[" + faces + "])";
}

// Span ends name a triangle's index modulo Polyhedron::kFaceIds: in a mesh of 172 800
// triangles each face id stands for two or three.
TEST(ExactMesh, AMeshOfMoreTrianglesThanFaceIdsByHand) {
    // A unit cube over its corner, no face of one in a plane of the other.
    const csg::Scene scene = compiled("difference() { " + finelyDividedCube(120) +
                                      "; translate([0.5, 0.5, 0.5]) cube(1); }");
    ASSERT_EQ(scene.leafCount(), 2u);
    const auto& cube = std::get<csg::Polyhedron>(scene.leafPrimitive(0));
    ASSERT_GT(cube.data->triangles.size(), 2 * size_t(csg::Polyhedron::kFaceIds));
    const TriangleMesh mesh = exactMesh(scene);
    EXPECT_NEAR(csg::signedVolume(mesh), 8.0 - 0.125, 1e-12);
}

// The divided cube moved by half its side across a corner of a box: the box's faces are cut
// along every edge of the divided cube's triangles that crosses them, and a piece left uncut
// where the divided cube's boundary crosses it (a cut its box was wrongly said to miss) would be
// kept or dropped whole. 8 - 1.5^3 by hand.
TEST(ExactMesh, FacesCutByManyTrianglesByHand) {
    const TriangleMesh mesh =
        exactMesh(compiled("difference() { cube(2, center = true); "
                           "translate([0.5, 0.5, 0.5]) " +
                           finelyDividedCube(40) + "; }"));
    EXPECT_NEAR(csg::signedVolume(mesh), 8.0 - 1.5 * 1.5 * 1.5, 1e-12);
}

TEST(ExactMesh, VolumeStaysUnderATurn) {
    const std::string part =
        "module part() { difference() { intersection() { cube(1, center=true); "
        "sphere(0.68, $fn=32); } cylinder(h=2, r=0.3, center=true, $fn=32); "
        "rotate([90,0,0]) cylinder(h=2, r=0.3, center=true, $fn=32); } }\n";
    const double upright = csg::signedVolume(exactMesh(compiled(part + "part();")));
    const double turned =
        csg::signedVolume(exactMesh(compiled(part + "rotate([13, 34, 7]) part();")));
    EXPECT_GT(upright, 0.3);
    EXPECT_NEAR(turned, upright, 1e-9 * upright);
}

// Teeth whose tops and bottoms lie in the disc's caps: where a tooth's top and the disc's top
// coincide, the lines through their pieces must name the same leaf, or both pieces are kept
// (an edge used three times) or neither (a hole). The top-level union's BVH merges the
// teeth in an order that changes from line to line; the union's tie-break names the lower
// leaf in any order (csg/SpanList.h). Three teeth were enough to lose the boundary before.
TEST(ExactMesh, TeethInTheDiscsCapsCloseTheBoundary) {
    const csg::Scene scene = compiled(
        "cylinder(h = 5, r = 20, $fn = 64);\n"
        "for (a = [0, 22.5, 45, 150]) rotate([0, 0, a]) translate([19, -2, 0]) cube([5, 4, 5]);");
    const TriangleMesh mesh = exactMesh(scene);
    // Against the part's volume by span quadrature, good to ~1e-3 on straight walls.
    EXPECT_NEAR(csg::signedVolume(mesh), csg::volume(scene, 1024), 2e-3 * csg::volume(scene, 1024));
}

// Debian's candleStand.scad, its cylinders faceted for an export: the stand's rings and arms
// share planes whose faces meet lines at t that differ by rounding, so the merge names one
// leaf here and another there; a span end on any coincident face facing the same way counts,
// and the lowest such leaf keeps the piece. Before, the boundary did not close.
TEST(ExactMesh, CoincidentFacesOfFacetedLeavesCloseTheBoundary) {
    const std::filesystem::path part = "/usr/share/openscad/examples/Parametric/candleStand.scad";
    if (!std::filesystem::exists(part))
        SKIP_OR_FAIL_IN_CI("Debian's openscad examples are missing");
    std::ifstream in(part);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const io::EvaluateResult r = csg::testing::evaluate(text);
    ASSERT_TRUE(r.ok()) << csg::testing::diagnosticsOf(r);
    const csg::Scene scene = csg::Scene::compile(r.model->root);
    const csg::NodePtr faceted =
        io::facetToDeviation(r.model->root, 0.05, csg::FacetFit::Inscribed);
    ASSERT_TRUE(faceted);
    const TriangleMesh mesh = exactMesh(csg::Scene::compile(faceted));
    // Within the faceting's reach of the exact part's volume (span quadrature, ~1e-3).
    EXPECT_NEAR(csg::signedVolume(mesh), csg::volume(scene, 1024), 5e-3 * csg::volume(scene, 1024));
}

// Debian's example007 in small: two crossing slots, each cut by the intersection of two prisms
// whose floors lie in one plane, from a post on a plate. The first slot's second prism reaches
// only as far as the first prism (|x| <= 2), so its floor is cut only by the faces near there;
// where it runs on under the second slot's floor it is one of three coincident faces, and it
// kept a piece that crossed the post's wall (the lowest leaf keeps a covered piece) although it
// bounds nothing outside its reach. The boundary did not close and the part took the grid.
TEST(ExactMesh, CoincidentFloorsKeepOnlyWhatTheirLeafReaches) {
    const csg::Scene scene = compiled(
        "difference() {\n"
        "  rotate_extrude($fn = 30) polygon([[0, 0], [11, 0], [11, 2], [5, 2], [5, 12], [0, "
        "12]]);\n"
        "  for (r = [0, 90]) rotate([0, 0, r]) intersection() {\n"
        "    translate([-2, -50, 3]) cube([4, 100, 28]);\n"
        "    translate([-50, -6, 3]) cube([100, 12, 28]);\n"
        "  }\n"
        "}");
    const TriangleMesh mesh = exactMesh(scene);
    // Against the part's volume by span quadrature, good to ~1e-3 on straight walls.
    EXPECT_NEAR(csg::signedVolume(mesh), csg::volume(scene, 1024), 2e-3 * csg::volume(scene, 1024));
}

// Solids that touch without sharing volume: no mesh with one vertex per position is a
// 2-manifold there (an edge of four triangles, a vertex at the apex of two cones), so the
// sheets are told apart (csg/mesh/TouchingSheets.h): each cube keeps its own 8 corners, and
// the contact is no self-intersection. Before, the boundary "did not close" and the part went
// to the grid.
TEST(ExactMesh, CubesTouchingAlongAnEdgeOrAtACornerAreTwoSheets) {
    for (const char* offset : {"[1, 1, 0]", "[1, 1, 1]"}) {
        const std::string part = std::string("cube(1); translate(") + offset + ") cube(1);";
        const TriangleMesh mesh = exactMesh(compiled(part));
        EXPECT_NEAR(csg::signedVolume(mesh), 2.0, 1e-12) << part;
        EXPECT_EQ(mesh.positions.size(), 16u) << part;
        EXPECT_EQ(mesh.triangles.size(), 24u) << part;

        // STL repeats positions and says nothing of which corners are one vertex: read back,
        // the welded sheets are told apart again, so compare finds a closed manifold.
        csg::testing::TempDir dir("csgray_touching_sheets");
        const auto stl = dir.path / "touching.stl";
        ASSERT_FALSE(io::writeMesh(stl, mesh, {}).has_value());
        const io::MeshReadResult back = io::readMesh(stl);
        ASSERT_TRUE(back.mesh.has_value()) << back.error;
        EXPECT_TRUE(csg::checkTopology(*back.mesh).closedManifold()) << part;
        EXPECT_EQ(back.mesh->positions.size(), 16u) << part;
    }
}

// Debian's example017 in small: a slot cut from a plate by a square turned in 2-D, inside
// linear_extrude, and the tab that fills it, a cube turned in 3-D. The slot's walls and the
// tab's sides are the same planes, so the union is the whole plate. The extrusion's outline
// went through Clipper's integers at 2^-28 of its size: the slot's corners moved by up to 1e-8,
// its walls tilted, and 3.5e-7 away the two planes' cuts no longer welded (io/ExtrusionMesh.cpp).
TEST(ExactMesh, ASlotTurnedIn2DMeetsATabTurnedIn3D) {
    const io::EvaluateResult r = csg::testing::evaluate(
        "linear_extrude(6) difference() { square(60, center = true);\n"
        "  for (a = [0, 120, 240]) rotate(a) translate([0, 20]) square([6, 10], center = true); }\n"
        "for (a = [0, 120, 240]) rotate([0, 0, a]) translate([-3, 15, 0]) cube([6, 10, 6]);");
    ASSERT_TRUE(r.ok()) << csg::testing::diagnosticsOf(r);
    csg::TessellateOptions options;
    options.tolerance = 0.01;
    options.facetCurves = io::curveFaceter(r.model->root);
    const csg::TessellateResult t = csg::tessellate(csg::Scene::compile(r.model->root), options);
    EXPECT_TRUE(t.exact);
    EXPECT_NEAR(std::abs(csg::signedVolume(t.mesh)), 60.0 * 60.0 * 6.0, 1e-9);
    EXPECT_TRUE(csg::checkTopology(t.mesh).closedManifold());
}

// Three Debian examples that went to the grid (README.md's claim). example017: the tripods' tabs
// fill slots cut in 2-D and the discs' corners touch the tripods' walls; before, its boundary
// did not close and the grid wrote a million triangles 0.44 off at a 0.2 tolerance, and then a
// mesh point where a disc's exact rim touches a wall tangentially was "out of reach" of every
// measuring line until the shifted measurements went up to tol::kDistanceShiftMaxFraction.
// projection: outlines projected from an STL leave corners 1e-7 apart, which the extrusion's
// cleaning now merges (io/ExtrusionMesh.cpp, kCleanBits); before, 3 012 grid triangles.
// example007 (at the export's own tolerance for it): the slots' coincident floors above
// (CoincidentFloorsKeepOnlyWhatTheirLeafReaches); before, 6 402 grid triangles in 3 s.
TEST(ExactMesh, DebiansExamplesThatTookTheGridAreTheirExactBoundary) {
    const std::pair<const char*, double> parts[] = {
        {"/usr/share/openscad/examples/Old/example017.scad", 0.2},
        {"/usr/share/openscad/examples/Old/example007.scad", 0.0864},
        {"/usr/share/openscad/examples/Basics/projection.scad", 0.132}};
    for (const auto& [path, tolerance] : parts) {
        const std::filesystem::path part = path;
        if (!std::filesystem::exists(part))
            SKIP_OR_FAIL_IN_CI("Debian's openscad examples are missing");
        const io::EvaluateResult r = io::evaluateFile(part);
        ASSERT_TRUE(r.ok()) << csg::testing::diagnosticsOf(r);
        csg::TessellateOptions options;
        options.tolerance = tolerance;
        options.facetCurves = io::curveFaceter(r.model->root);
        const csg::TessellateResult t =
            csg::tessellate(csg::Scene::compile(r.model->root), options);
        EXPECT_TRUE(t.exact) << path;
        EXPECT_TRUE(t.toleranceMet) << path;
        EXPECT_TRUE(csg::checkTopology(t.mesh).closedManifold()) << path;
        EXPECT_EQ(csg::findSelfIntersections(t.mesh).pairs, 0u) << path;
        EXPECT_LT(t.mesh.triangles.size(), 3000u) << path;
    }
}

TEST(ExactMesh, CurvedPartsFallBackToTheGrid) {
    const csg::Scene scene = compiled("difference() { cube(1, center=true); sphere(0.6); }");
    EXPECT_FALSE(csg::allLeavesPolyhedral(scene));
    csg::PolyhedralBoundaryStats stats;
    EXPECT_FALSE(csg::polyhedralBoundary(scene, 0, &stats).has_value());
    ASSERT_NE(stats.declined, nullptr);
    csg::TessellateOptions options;
    options.tolerance = 0.1;
    options.maxPasses = 1;
    options.simplify = false;
    EXPECT_FALSE(csg::tessellate(scene, options).exact);
}

TEST(ExactMesh, TessellateUsesItAndMeasuresIt) {
    csg::TessellateOptions options;
    options.tolerance = 1e-3;
    const csg::TessellateResult r =
        csg::tessellate(compiled("difference() { cube(2, center=true); cube(1); }"), options);
    EXPECT_TRUE(r.exact);
    EXPECT_TRUE(r.toleranceMet);
    EXPECT_NEAR(csg::signedVolume(r.mesh), 7.0, 1e-12);
    // Exact surface points lie on the mesh to rounding.
    EXPECT_LE(r.backError.max, 1e-12);
}

// A torus of revolution exported at a tolerance of 0.0018 is faceted into more triangles than
// span ends can name one by one (Polyhedron::kFaceIds): it is still its exact boundary, not the
// grid's mesh (277 228 triangles at 0.0025, in 5.4 s, before), and within the tolerance. Its volume
// is Pappus's 2 pi R * pi r^2, which the mesh misses by at most its area 4 pi^2 R r times T.
TEST(ExactMesh, AFineTorusIsItsExactBoundary) {
    const io::EvaluateResult r =
        csg::testing::evaluate("rotate_extrude() translate([10, 0]) circle(3);");
    ASSERT_TRUE(r.ok()) << csg::testing::diagnosticsOf(r);
    csg::TessellateOptions options;
    options.tolerance = 0.0018;
    options.facetCurves = io::curveFaceter(r.model->root);
    const csg::TessellateResult t = csg::tessellate(csg::Scene::compile(r.model->root), options);
    EXPECT_TRUE(t.exact);
    EXPECT_TRUE(t.toleranceMet);
    EXPECT_GT(t.mesh.triangles.size(), size_t(csg::Polyhedron::kFaceIds));
    EXPECT_LT(t.mesh.triangles.size(), 100000u);
    EXPECT_TRUE(csg::checkTopology(t.mesh).closedManifold());
    const double pi = std::numbers::pi;
    EXPECT_NEAR(csg::signedVolume(t.mesh), 2.0 * pi * pi * 10.0 * 9.0,
                4.0 * pi * pi * 10.0 * 3.0 * options.tolerance);
}

// The peer part of bench/README.md's export tables (../shared/peers/part1.scad: a cube cut by
// OpenSCAD's $fn = 64 sphere, bored three ways) is the same polyhedron in csgray and OpenSCAD:
// the volumes agree to OpenSCAD's float STL, and csgray writes no more triangles than OpenSCAD.
constexpr const char* kPeerPart = R"($fn = 64;
difference() {
  intersection() { cube(1, center=true); sphere(0.68); }
  cylinder(h=2, r=0.3, center=true);
  rotate([90,0,0]) cylinder(h=2, r=0.3, center=true);
  rotate([0,90,0]) cylinder(h=2, r=0.3, center=true);
}
)";

TEST(ExactMesh, PeerPartMatchesOpenScadsMesh) {
    if (std::system("openscad --version >/dev/null 2>&1") != 0)
        SKIP_OR_FAIL_IN_CI("openscad is not installed");
    csg::testing::TempDir dir("csgray_exact_mesh");
    const auto part = dir.path / "part1.scad";
    std::ofstream(part) << kPeerPart;
    const auto stl = dir.path / "part1.stl";
    const std::string command = "openscad --export-format binstl -o '" + stl.string() + "' '" +
                                part.string() + "' >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const io::MeshReadResult theirs = io::readMesh(stl);
    ASSERT_TRUE(theirs.mesh.has_value()) << theirs.error;

    const TriangleMesh ours = exactMesh(compiled(kPeerPart));
    const double volume = csg::signedVolume(ours);
    // OpenSCAD's STL rounds its vertices to floats (6e-8 relative of ~0.5): a volume error of
    // that times the surface area (~5), 3e-7; 1e-6 leaves room.
    EXPECT_NEAR(volume, csg::signedVolume(*theirs.mesh), 1e-6);
    EXPECT_LE(ours.triangles.size(), theirs.mesh->triangles.size());
    std::printf("csgray %zu triangles, OpenSCAD %zu; volumes %.9f and %.9f\n",
                ours.triangles.size(), theirs.mesh->triangles.size(), volume,
                csg::signedVolume(*theirs.mesh));
}

}  // namespace
