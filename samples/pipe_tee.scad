// A pipe tee: a straight run along x with a branch along +y, hollowed by bores that meet.
outer_r = 10;
wall = 2;
run = 60;       // length of the straight run, centred on the origin
branch = 30;    // from the run's axis to the branch's end

module tube(length, r) {
    rotate([0, 90, 0]) cylinder(h = length, r = r, center = true);
}

difference() {
    union() {
        tube(run, outer_r);
        rotate([-90, 0, 0]) cylinder(h = branch, r = outer_r);
    }
    tube(run + 2, outer_r - wall);
    rotate([-90, 0, 0]) cylinder(h = branch + 1, r = outer_r - wall);
}
