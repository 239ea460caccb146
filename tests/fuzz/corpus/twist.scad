// linear_extrude with twist and scale = [sx, sy] (primitives/TwistedExtrusion.h): ordinary
// parts, degenerate scales and absurd twists must evaluate, compile and answer a ray.
linear_extrude(height = 10, twist = 90) square(2, center = true);
linear_extrude(height = 3, twist = -400, scale = [2, 0.5], center = true, slices = 3)
    difference() { square(4, center = true); translate([1, 0]) circle(0.5); }
linear_extrude(height = 6, twist = 360, scale = 0) translate([0.5, 0]) square(1);
linear_extrude(height = 6, twist = 45, scale = [0, 1.5]) circle(1, $fn = 7);
linear_extrude(height = 6, scale = [-1, 2]) square(1);
linear_extrude(height = 1e-9, twist = 1e6) square(1);
linear_extrude(height = 1, twist = 1e300) square(1);
linear_extrude(height = 1, scale = [1e300, 1]) square(1);
linear_extrude(height = 1, twist = 1e-300, scale = [1, 1 + 1e-15]) translate([-100, 0]) circle(3);
linear_extrude(1, scale = [1, 2, 3]) square(1);
