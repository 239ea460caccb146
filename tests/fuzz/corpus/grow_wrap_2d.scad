// 2-D shapes grown, wrapped, cut and extruded, good and bad: text with odd strings, offset,
// hull, minkowski, projection, polygon paths, twisted extrusions of text and of holes.
text("csgray");
translate([0, 20]) text("Åé 漢 😀 \u00e9", size = 5, halign = "center", valign = "top");
text("", size = 3);
text(str(1 / 3), font = "Liberation Sans:style=Bold", spacing = 1.5, direction = "ttb");
text("x", size = -1);
offset(r = 1) square(4);
offset(delta = -0.5, chamfer = true) polygon([[0, 0], [6, 0], [3, 5]]);
offset(r = -10) circle(2);
hull() { circle(1); translate([5, 2]) square(1); }
minkowski() { square(2); circle(0.5); }
minkowski() { polygon([[0, 0], [4, 0], [4, 4], [2, 1], [0, 4]]); square(0.5, center = true); }
projection(cut = true) translate([0, 0, -0.5]) cube(2);
projection() rotate([30, 40, 0]) cylinder(r = 1, h = 3);
polygon(points = [[0, 0], [10, 0], [10, 10], [0, 10], [2, 2], [8, 2], [8, 8], [2, 8]],
        paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
polygon([[0, 0], [1, 1], [2, 0], [0, 1], [2, 1]]);
polygon(points = [[0, 0], [1, 0]], paths = [[0, 1, 7]]);
resize([10, 0], auto = true) circle(1);
mirror([1, 0]) scale([2, -1]) square([1, 2]);
difference() { square(10, center = true); circle(3); rotate(45) square([12, 1], center = true); }
intersection() { circle(5, $fn = 7); square(4); }
linear_extrude(height = 5, twist = 180, scale = [1, 0.5]) text("tw", size = 4);
linear_extrude(height = 3, twist = -90) difference() { square(6, center = true); circle(2); }
rotate_extrude() difference() { translate([-5, 0]) square(10); translate([-6, -1]) square([6, 12]); }
