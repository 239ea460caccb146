// A die: a cube with rounded corners (cube intersected with a sphere) and hemispherical pips;
// opposite faces add up to seven.
side = 20;
round_r = 14;
pip_r = 2;
s = side / 2;
o = side / 4;   // pip offset from a face's centre

// Pip positions on a face, in the face's own (u, v) coordinates.
function pips(n) =
    n == 1 ? [[0, 0]] :
    n == 2 ? [[o, o], [-o, -o]] :
    n == 3 ? [[o, o], [0, 0], [-o, -o]] :
    n == 4 ? [[o, o], [o, -o], [-o, o], [-o, -o]] :
    n == 5 ? [[o, o], [o, -o], [0, 0], [-o, o], [-o, -o]] :
             [[o, o], [o, 0], [o, -o], [-o, o], [-o, 0], [-o, -o]];

// Face n's pips: the face's normal axis and sign, then (u, v) on the other two axes.
module face(n, axis, sign) {
    for (p = pips(n))
        translate(axis == 0 ? [sign * s, p[0], p[1]] :
                  axis == 1 ? [p[0], sign * s, p[1]] : [p[0], p[1], sign * s])
            sphere(r = pip_r);
}

difference() {
    intersection() {
        cube(side, center = true);
        sphere(r = round_r);
    }
    face(1, 2, 1);
    face(6, 2, -1);
    face(2, 0, 1);
    face(5, 0, -1);
    face(3, 1, 1);
    face(4, 1, -1);
}
