// A pipe flange: a disc with a hub, a through bore and a circle of bolt holes.
disc_r = 40;
disc_h = 8;
hub_r = 20;
hub_h = 25;
bore_r = 12;
bolts = 6;
bolt_circle = 30;
bolt_r = 4;

difference() {
    union() {
        cylinder(h = disc_h, r = disc_r);
        cylinder(h = hub_h, r = hub_r);
    }
    translate([0, 0, -1]) cylinder(h = hub_h + 2, r = bore_r);
    for (a = [0:360 / bolts:359])
        rotate([0, 0, a]) translate([bolt_circle, 0, -1]) cylinder(h = disc_h + 2, r = bolt_r);
}
