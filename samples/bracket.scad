// An L-shaped mounting bracket: a base plate and an upright, with bolt holes through both.
length = 40;     // along x
width = 20;      // along y
thickness = 4;
height = 30;     // of the upright
hole_d = 6;

module bolt_hole(depth) {
    // Longer than the plate so the cut leaves no skin.
    cylinder(h = depth + 2, d = hole_d, center = true);
}

difference() {
    union() {
        cube([length, width, thickness]);                    // base plate
        cube([thickness, width, height]);                    // upright
    }
    // Two holes through the base.
    for (x = [15, 30])
        translate([x, width / 2, thickness / 2]) bolt_hole(thickness);
    // One hole through the upright, along x.
    translate([thickness / 2, width / 2, 20])
        rotate([0, 90, 0]) bolt_hole(thickness);
}
