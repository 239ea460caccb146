// The CSG emblem: a cube intersected with a sphere, with three cylinders drilled through
// along x, y and z. The classic picture of constructive solid geometry.
size = 2;          // edge of the cube, centred on the origin
ball = 1.35;       // radius of the sphere that rounds the cube's corners
bore = 0.6;        // radius of the three drilled holes

difference() {
    intersection() {
        cube(size, center = true);
        sphere(r = ball);
    }
    cylinder(h = 1.5 * size, r = bore, center = true);                    // along z
    rotate([90, 0, 0]) cylinder(h = 1.5 * size, r = bore, center = true);  // along y
    rotate([0, 90, 0]) cylinder(h = 1.5 * size, r = bore, center = true);  // along x
}
