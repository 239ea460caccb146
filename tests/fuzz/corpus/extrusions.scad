// linear_extrude and rotate_extrude in OpenSCAD 2021's forms, good and bad.
linear_extrude(10) square(2);
linear_extrude(height = 4, center = true, scale = 0) circle(1);
linear_extrude(height = 4, scale = 2.5, convexity = 3) polygon([[0, 0], [2, 0], [1, 3]]);
linear_extrude(height = -1) square();
linear_extrude(height = 3, scale = [1, 2]) square();
linear_extrude(height = 3, twist = 90, slices = 10) square();
linear_extrude(5, true) square();
linear_extrude(file = "x.dxf") square();
linear_extrude(2) cube();
rotate_extrude() translate([2, 0]) circle(1);
rotate_extrude(angle = 90, $fn = 12) translate([1, 0]) square([1, 2]);
rotate_extrude(angle = -450) translate([-3, 0]) square([1, 1]);
rotate_extrude(angle = 0) square();
rotate_extrude(90) square();
rotate_extrude($fn = 3) translate([1, -1]) polygon([[0, 0], [1, 0], [0.5, 2]]);
rotate_extrude() translate([-1, 0]) square([2, 1]);
translate([0, 0, 1]) rotate([10, 20, 30]) linear_extrude(1) circle(1e-300);
