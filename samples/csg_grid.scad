// A 3 x 3 x 3 grid of CSG emblems, each turned a little differently: the peer benchmark
// scene (../shared/peers/csg_grid3.scad). Its $fn = 64 makes every sphere and cylinder
// OpenSCAD's polyhedron (--curves auto); --curves exact gives the exact surfaces.
$fn = 64;
spacing = 1.2;

module part() {
    difference() {
        intersection() {
            cube(1, center = true);
            sphere(0.68);
        }
        cylinder(h = 2, r = 0.3, center = true);
        rotate([90, 0, 0]) cylinder(h = 2, r = 0.3, center = true);
        rotate([0, 90, 0]) cylinder(h = 2, r = 0.3, center = true);
    }
}

for (i = [0:2], j = [0:2], k = [0:2])
    translate([i * spacing, j * spacing, k * spacing])
        rotate([i * 13, j * 17, k * 7])
            part();
