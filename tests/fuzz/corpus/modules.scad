module ring(r = 5, n = 4) {
    for (i = [0:n - 1]) rotate([0, 0, i * 360 / n]) translate([r, 0, 0]) children();
}
module pick() { children(0); children([1:$children - 1]); echo($children); }
ring(n = 6) sphere(1);
pick() { cube(1); translate([2, 0, 0]) cube(1); sphere(2); }
