// 2-D shapes, their transforms and booleans, and OpenSCAD's dimension rules.
square();
square(3, center = true);
square([2, 0]);
square("x");
circle(2);
circle(d = 3, $fn = 6);
circle(-1);
polygon([[0, 0], [4, 0], [4, 4], [0, 4], [1, 1], [3, 1], [3, 3], [1, 3]], [[0, 1, 2, 3], [4, 5, 6, 7]]);
polygon([[0, 0], [1, 0]]);
polygon([[0, 0], [1, 0], [0, 1]], [[0, 1, 9]]);
polygon(points = [[0, 0, 5], [1, 0], [0, 1]]);
translate([1, 2]) rotate(30) scale([2, 1]) mirror([1, 1]) square();
rotate([90, 0, 0]) square();
multmatrix([[1, 0.5, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0]]) circle(1);
difference() { circle(3); square(2, center = true); }
intersection() { circle(1); translate([1, 0]) circle(1); }
union() { square(2); cube(1); }
union() { cube(1); square(2); }
color("red") polygon([[0, 0], [1e300, 0], [0, 1e300]]);
