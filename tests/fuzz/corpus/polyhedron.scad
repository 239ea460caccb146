// polyhedron(): OpenSCAD's cube, the deprecated triangles=, out-of-range and negative indices,
// a 2-D point, a non-convex face, an open mesh; import() of a file the fuzzer may not read.
p = [[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]];
f = [[0,1,2,3],[4,5,1,0],[7,6,5,4],[5,6,2,1],[6,7,3,2],[7,4,0,3]];
polyhedron(p, f, convexity = 2);
translate([2, 0, 0]) polyhedron(points = p, triangles = f);
translate([4, 0, 0]) polyhedron(points = concat(p, [[0.5, 0.5]]), faces = [for (x = f) concat(x, [99, -1])]);
translate([0, 2, 0]) polyhedron([[0,0,0],[2,0,0],[2,1,0],[1,1,0],[1,2,0],[0,2,0],[0,0,1]],
                                [[0,1,2,3,4,5],[0,6,1],[1,6,2],[2,6,3],[3,6,4],[4,6,5],[5,6,0]]);
translate([0, 4, 0]) polyhedron(p, [for (i = [0:4]) f[i]]);
difference() { cube(3); polyhedron(p, f); }
import("part.stl");
