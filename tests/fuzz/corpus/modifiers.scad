#cube(1);
%sphere(2);
*cylinder(h = 1, r = 1);
translate([5, 0, 0]) !sphere(1);
difference() { cube(3); #sphere(2); }
