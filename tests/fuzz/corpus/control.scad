x = 3;
if (x > 2) cube(x); else sphere(x);
if (x < 0) sphere(1);
let (a = 2, b = a * 2) translate([b, 0, 0]) sphere(a);
assert(x == 3, "x must be 3");
echo(assert(true) 5, echo("inner") 6, let (q = 1) q + 1);
assign(z = 4) cube(z);
