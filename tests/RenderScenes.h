// Test support: part sources shared by render_test (the renderer in process) and
// cli_render_test (the same scenes through `csgray render`). Not for product code.
#pragma once

#include <string>

namespace csg::testing {

// Two facing mirrors, z <= 0 and z >= 10, seen by an orthographic camera at z = 5 looking
// down: every primary ray hits the floor and the reflections bounce between the two planes
// forever, so the ray tree is cut only by the weight rule. The k-th reflection ray weighs
// reflect^k and is cast when reflect^k >= 1/256.
inline std::string facingMirrors(double reflect) {
    return "camera(eye=[0,0,5], center=[0,0,0], up=[0,1,0], projection=\"orthographic\");\n"
           "material(ambient=0.2, diffuse=0, specular=0, reflect=" +
           std::to_string(reflect) +
           ") {\n"
           "  halfspace([0, 0, 1], 0);\n"
           "  halfspace([0, 0, -1], -10);\n"
           "}\n";
}

// A white plane z <= 0 (ambient 0, diffuse 1: a pixel is the light's cosine, nothing else),
// seen straight down by an orthographic camera at z = 1 whose view is 4 x 4 units; pixel
// (i, j) of an 8 x 8 image has its centre at x = -2 + (i + 0.5) / 2, y = 2 - (j + 0.5) / 2.
// The light is at (0, 0, 100); slabs are added as given.
inline std::string planeUnder(const std::string& slabs) {
    return "camera(eye = [0, 0, 1], center = [0, 0, -9], up = [0, 1, 0], fov = 2 * atan(0.2), "
           "projection = \"orthographic\");\n"
           "light([0, 0, 100]);\n"
           "material(color = [1, 1, 1], ambient = 0, diffuse = 1, specular = 0) "
           "halfspace([0, 0, 1], 0);\n" +
           slabs;
}

}  // namespace csg::testing
