// A control knob: a tapered body with grip flutes, a domed cap and a D-shaped shaft hole.
body_r = 15;
body_h = 16;
flutes = 12;
flute_r = 2;
shaft_r = 3;
shaft_flat = 1;     // how much of the shaft circle the flat cuts off
shaft_depth = 12;

intersection() {
    difference() {
        union() {
            cylinder(h = body_h, r1 = body_r, r2 = body_r - 2);
            translate([0, 0, body_h]) scale([1, 1, 0.4]) sphere(r = body_r - 2);
        }
        for (i = [0:flutes - 1])
            rotate([0, 0, i * 360 / flutes + 15])
                translate([body_r, 0, 2]) cylinder(h = body_h + 10, r = flute_r);
        // The D-shaped shaft hole: a cylinder minus the flat.
        translate([0, 0, -1]) difference() {
            cylinder(h = shaft_depth + 1, r = shaft_r);
            translate([shaft_r - shaft_flat, -shaft_r, -1]) cube([shaft_r, 2 * shaft_r, shaft_depth + 3]);
        }
    }
    // Nothing below the floor.
    translate([-50, -50, 0]) cube(100);
}
