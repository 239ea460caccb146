// The CSG emblem as a scene: csgray's scene modules (camera, light, background, material)
// around the part. OpenSCAD does not know these modules (it warns and ignores them), so this
// file is for csgray; the plain part is emblem.scad.
camera(eye = [4, -5, 3], center = [0, 0, 0], up = [0, 0, 1], fov = 35);
light(position = [5, -3, 8], color = [1, 1, 1], intensity = 1);
background([0.12, 0.14, 0.18]);

material(color = [0.8, 0.15, 0.1], specular = 0.5, shininess = 64)
    difference() {
        intersection() {
            cube(2, center = true);
            sphere(r = 1.35);
        }
        material(color = [0.9, 0.9, 0.95]) {
            cylinder(h = 3, r = 0.6, center = true);
            rotate([90, 0, 0]) cylinder(h = 3, r = 0.6, center = true);
            rotate([0, 90, 0]) cylinder(h = 3, r = 0.6, center = true);
        }
    }
