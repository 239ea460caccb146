// A gear-like ring: a thick washer with square teeth around its rim.
teeth = 16;
outer_r = 20;
inner_r = 12;
thickness = 5;
tooth = [5, 4];   // radial length, tangential width

module tooth_at(angle) {
    rotate([0, 0, angle])
        translate([outer_r - 1, -tooth[1] / 2, 0])
            cube([tooth[0], tooth[1], thickness]);
}

difference() {
    union() {
        cylinder(h = thickness, r = outer_r);
        for (i = [0:teeth - 1]) tooth_at(i * 360 / teeth);
    }
    translate([0, 0, -1]) cylinder(h = thickness + 2, r = inner_r);
}
