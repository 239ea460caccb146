cube("big"); sphere(r = [1]); cylinder(h = true); translate(5) cube(); scale(0) cube();
multmatrix([[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]]) cube(); torus(1, 2);
