// The scenes and ray sets the benchmarks share, built in C++ (the part language comes in another
// issue). Every scene is deterministic (fixed seeds), so figures from two runs compare.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "csg/Ray.h"
#include "csg/Scene.h"
#include "csg/Tree.h"

namespace csg::bench {

// A pinhole camera in the manner of POV-Ray: horizontalFovDegrees is POV's `angle`, the image
// plane is square (POV's default `right x up y`), and rays have unit direction so t is the
// distance from the eye.
struct PinholeCamera {
    Vec3 eye;
    Vec3 lookAt;
    Vec3 up{0.0, 1.0, 0.0};
    double horizontalFovDegrees = 40.0;

    // One ray through the centre of each pixel of a width x height grid, row by row.
    std::vector<Ray> pixelRays(int width, int height) const;
};

// A scene the benchmarks can query, with the cost of getting there.
struct BenchScene {
    Scene scene;
    std::vector<Ray> rays;
    size_t leafCount = 0;
    double compileSeconds = 0.0;  // Scene::compile of the scene's tree, first touch included
};

// Scene::compile of a tree is timed once and the compiled scene kept for the whole process, so
// the `closest` and `spans` benchmarks (and their repetitions) of one scene share one compile.
// Keys: "sphere", "emblem_grid", "sphere_layer/<n>", "sphere_layer_narrow/<n>".
const BenchScene& cachedScene(const std::string& key);

// One sphere of radius 1 at the origin, seen from 4 units away through a square frame that
// circumscribes its silhouette: about pi/4 of the rays hit, the corners miss.
NodePtr singleSphereTree();
PinholeCamera singleSphereCamera();

// The emblem grid of shared/peers/csg_grid.pov: 10 x 10 x 10 parts, part (I, J, K) being
// (box [-0.5, 0.5]^3 ∩ sphere r = 0.68) − three cylinders r = 0.3 of length 2 along x, y, z,
// rotated by <13 I, 17 J, 7 K> degrees (about x, then y, then z, as POV-Ray does) and
// translated to <I, J, K>.
NodePtr emblemGridTree();
PinholeCamera emblemGridCamera();  // POV's camera: location <14,12,-22>, look_at 4.5, angle 40

// n spheres at seeded random positions in a thin layer 100 x 100 in x, y. The radius shrinks as
// 1/sqrt(n) so the layer covers the same fraction of the view at every n: a ray meets the same
// expected number of spheres (about 0.5 straight down) whatever n is, which is what makes the
// BVH's node visits per ray comparable across n (they should grow as log n).
NodePtr sphereLayerTree(size_t sphereCount);
PinholeCamera sphereLayerCamera();
// The same n spheres of the same radius, clustered: gathered in 16 balls of radius 4 (seeded
// centres across the layer, uniform in each ball) instead of spread over the layer, so
// most of the layer is empty and a few spots are dense: the case a uniform grid handles badly.
NodePtr clusteredLayerTree(size_t sphereCount);
// A terrain of about n triangles as one mesh (a polyhedron leaf): the height field
// z = 2 + 1.5 sin(0.23 x) cos(0.31 y) + 0.8 sin(0.9 x + 0.6 y) over the same 100 x 100 layer,
// sampled on a square lattice (two triangles per square), closed by walls down to z = -1 and a
// floor. What an imported scan or STL terrain is: many small faces along a surface. Seen by the
// layer's camera, every pixel but the sky's meets it.
NodePtr terrainMeshTree(size_t triangleCount);
// The same camera narrowed to 0.4 degrees: its rays cover about 1 x 1 unit of the layer's
// centre, so they walk the same BVH but touch only the few nodes and leaves above that patch:
// the working set fits in cache at every n.
PinholeCamera sphereLayerNarrowCamera();

}  // namespace csg::bench
