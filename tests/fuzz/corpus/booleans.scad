difference() { cube(10, center = true); sphere(6); cylinder(h = 20, r = 2, center = true); }
intersection() { sphere(6); cube(10, center = true); }
union() { cube(1); translate([0.5, 0, 0]) cube(1); }
group() { sphere(1); }
render(convexity = 2) cube(1);
difference() { } intersection() { cube(1); cube(0); }
