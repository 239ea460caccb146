// A table: a top on four legs joined by an apron. Legs and top share faces, which a ray
// sees as one solid.
top = [100, 60, 4];
height = 74;          // floor to the top's upper face
leg = 5;
apron_h = 8;

module leg_at(x, y) {
    translate([x, y, 0]) cube([leg, leg, height - top[2]]);
}

union() {
    translate([0, 0, height - top[2]]) cube(top);
    for (x = [0, top[0] - leg], y = [0, top[1] - leg]) leg_at(x, y);
    // The apron: a frame under the top, between the legs.
    difference() {
        translate([leg, leg, height - top[2] - apron_h])
            cube([top[0] - 2 * leg, top[1] - 2 * leg, apron_h]);
        translate([2 * leg, 2 * leg, height - top[2] - apron_h - 1])
            cube([top[0] - 4 * leg, top[1] - 4 * leg, apron_h + 2]);
    }
}
