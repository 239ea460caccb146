// A chess pawn from primitives: a conical foot, a tapering stem, a collar and a round head.
module pawn() {
    cylinder(h = 3, r1 = 10, r2 = 8);                             // foot
    translate([0, 0, 3]) cylinder(h = 15, r1 = 6, r2 = 3);        // stem
    translate([0, 0, 14]) cylinder(h = 1.5, r = 5);               // collar
    translate([0, 0, 21]) sphere(r = 5);                          // head
}

pawn();
