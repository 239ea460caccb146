// A cut gem: an octahedron written as a polyhedron (faces clockwise seen from outside, as
// OpenSCAD wants them), its girdle trimmed by a box and a bore down its axis.
difference() {
    intersection() {
        polyhedron(points = [[10, 0, 0], [-10, 0, 0], [0, 10, 0], [0, -10, 0], [0, 0, 10],
                             [0, 0, -10]],
                   faces = [[0, 4, 2], [0, 2, 5], [0, 3, 4], [0, 5, 3],
                            [1, 2, 4], [1, 5, 2], [1, 4, 3], [1, 3, 5]]);
        cube([14, 14, 12], center = true);
    }
    cylinder(r = 2, h = 30, center = true);
}
