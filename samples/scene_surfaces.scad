// Polynomial surfaces (issue 5): a torus and a quartic "rounded cube" x^4 + y^4 + z^4 <= 1,
// the cube cut by a sphere of the same family so the quartic's cross-section shows. torus()
// and surface() are csgray's (OpenSCAD's surface() reads heightmaps), so this file is
// csgray-only, like the other scene_*.scad files.
camera(eye = [5, -7, 4.5], center = [0.8, 0, 0], up = [0, 0, 1], fov = 35);
light(position = [6, -4, 9], color = [1, 1, 1], intensity = 1);
background([0.12, 0.14, 0.18]);

// The torus around the z axis, tilted to show its hole.
material(color = [0.85, 0.55, 0.15], specular = 0.4, shininess = 48)
    translate([-1.4, 0, 0]) rotate([60, 0, 0]) torus(R = 1, r = 0.35);

// The rounded cube, its top corner cut away by a ball: the quartic meets a quadric exactly.
material(color = [0.2, 0.5, 0.85], specular = 0.5, shininess = 64)
    translate([1.6, 0, 0]) difference() {
        surface(f = "x^4 + y^4 + z^4 - 1", bbox = [[-1.1, -1.1, -1.1], [1.1, 1.1, 1.1]],
                solver = "auto");
        surface(f = "(x - 1)^2 + (y + 1)^2 + (z - 1)^2 - 0.8", bbox = [[0, -2, 0], [2, 0, 2]]);
    }
