// The plane of bench/scenes/torus_mirror.scad alone (its camera, light and checker): what a
// pixel costs csgray's render without any solid to solve beyond one half-space, measured with
// --max-depth 0 --no-shadows (bench/README.md, "Where the mirror torus's 1.98x went").
camera(eye = [0, -9, 6], center = [0, 0, 0], up = [0, 0, 1], fov = 45);
light([10, -10, 20]);
material(color = [0.1, 0.1, 0.1], color2 = [1, 1, 1], pattern = "checker", scale = 1, ambient = 0.1,
         diffuse = 0.8, specular = 0)
    halfspace([0, 0, 1], -1);
