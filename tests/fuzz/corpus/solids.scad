cube(); cube(2); cube([1, 2, 3], center = true); cube(size = 0);
sphere(); sphere(2); sphere(d = 3, $fn = 12); sphere(r = -1);
cylinder(); cylinder(h = 2, r = 1); cylinder(h = 3, r1 = 2, r2 = 0, center = true);
cylinder(h = 1, d = 2); cylinder(h = 1, d1 = 4, d2 = 2); cylinder(5, 2, 1);
halfspace([0, 0, 1], 2); halfspace(normal = [1, 1, 0], offset = -1);
torus(3, 1); torus(R = 5, r = 0.5);
