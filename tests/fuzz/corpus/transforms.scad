translate([1, 2, 3]) rotate([10, 20, 30]) scale([1, 2, 3]) cube(1);
rotate(45) rotate(a = 30, v = [1, 1, 0]) mirror([1, 0, 0]) sphere(1);
scale(2) translate([1, 0]) cube(1);
multmatrix([[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]) cube(1);
multmatrix([[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0]]) sphere(1);
color("red") color([0, 1, 0, 0.5]) color("#0000ff") color(c = "steelblue", alpha = 0.3) cube(1);
