// One leaf of a butt hinge: a plate with two knuckles around a pin hole along z. The other
// leaf's knuckles would fill the gap between z = 10 and z = 20.
knuckle_r = 4;
knuckle_h = 10;
pin_r = 1.5;
leaf = [30, 2, 30];   // x, y, z of the plate

difference() {
    union() {
        translate([knuckle_r / 2, -leaf[1] / 2, 0]) cube(leaf);
        for (z = [0, 2 * knuckle_h]) translate([0, 0, z]) cylinder(h = knuckle_h, r = knuckle_r);
    }
    cylinder(h = 100, r = pin_r, center = true);
}
