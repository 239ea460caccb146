// A vase drawn in 2-D and extruded, exactly: its wall is a profile revolved about z (the
// straight edges sweep cones, the round lip a torus), standing on a hexagonal foot extruded
// with a taper (scale), with a slot cut through the foot. No facets anywhere.
wall = 1.2;

module profile() {
    polygon([[0, 0], [9, 0], [12, 6], [13, 14], [10, 24], [8, 30], [8, 34],
             [8 - wall, 34], [8 - wall, 30], [10 - wall, 24], [13 - wall, 14],
             [12 - wall, 6], [9 - wall, wall], [0, wall]]);
    translate([8 - wall / 2, 34]) circle(d = wall);  // the rounded lip
}

translate([0, 0, 3.5]) rotate_extrude() profile();  // sunk into the foot: no shared face

difference() {
    linear_extrude(height = 4, scale = 0.8) rotate(30) circle(r = 14, $fn = 6);
    translate([0, 0, 2]) linear_extrude(height = 3, center = true) square([30, 3], center = true);
}
