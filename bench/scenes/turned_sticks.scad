// n^3 sticks (1.2 x 0.12 x 0.12) turned every way on a unit lattice: each stick's axis box
// is far looser than the stick, the case Kay and Kajiya's slab polyhedra are for
// (--bounds=slabs; bench/README.md, "Bounding volumes"). -D n=20 makes 8000.
n = 10;

camera(eye = [14, -22, 12] * n / 10, center = [4.5, 4.5, 4.5] * n / 10, up = [0, 0, 1], fov = 40);
light([30, -30, 40] * n / 10);
for (i = [0:n - 1], j = [0:n - 1], k = [0:n - 1])
    translate([i, k, j]) rotate([i * 37 + 11, j * 53 + 7, k * 71 + 3])
        cube([1.2, 0.12, 0.12], center = true);
