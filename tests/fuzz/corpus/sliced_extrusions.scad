// OpenSCAD's sliced extrusions (--curves openscad by this file's length: see FuzzInput.h).
linear_extrude(10, twist = 90, scale = [0.5, 0]) translate([1, 0]) square([2, 1]);
linear_extrude(5, twist = -700, slices = 7, center = true) difference() { circle(3, $fn = 9); square(1, center = true); }
linear_extrude(8, scale = [1, 2], $fs = 0.5) { square(2); translate([1, 1]) circle(1); }
linear_extrude(4, twist = 45, scale = 0) text("g", size = 3);
