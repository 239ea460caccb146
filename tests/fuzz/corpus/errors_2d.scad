// A profile on both sides of the axis: OpenSCAD's error at the call.
rotate_extrude() translate([-1, 0]) square([3, 1]);
