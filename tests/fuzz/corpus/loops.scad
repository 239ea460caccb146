for (i = [0:3], j = [i:3]) translate([i, j, 0]) cube(0.5);
for (p = [[0, 0, 0], [1, 1, 1]]) translate(p) sphere(0.2);
for (k = [10:-2:0]) echo(k);
for (ch = "héllo") echo(ch);
intersection_for (a = [0, 60, 120]) rotate([0, 0, a]) cube([10, 2, 2], center = true);
