// The peer benchmark ../shared/peers/torus_glass.pov in csgray's language: the seed thesis'
// torus (R = 2, r = 1), glass (ior 1.5), with the box [-4, 4] x [0.2, 2] x [-4, 0] (POV
// coordinates) cut out of it, over the checker plane of torus_mirror.scad. POV <x, y, z> is
// [x, z, y] here (see csg_grid.scad), so the box is [-4, 4] x [-4, 0] x [0.2, 2].
//
// POV's pigment rgbf <0.95, 0.95, 1, 0.9> filters 0.9 of the light through the colour: here
// transmit = 0.9 with that colour, which tints the light of shadow rays through the glass the
// same way (the refracted ray is weighted by transmit alone). POV's max_trace_level 8 is
// --max-depth 7 (the primary ray is POV's level 1), which bench/peer_render.sh passes.
//
// -D flat=true: the plane and the glass in flat colours (linear 0.2 and 1), opaque, on black,
// for the silhouette comparison.
flat = false;

function srgb(x) = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;

camera(eye = [0, -9, 6], center = [0, 0, 0], up = [0, 0, 1], fov = 45);
light([10, -10, 20]);
background(flat ? [0, 0, 0] : [srgb(0.2), srgb(0.3), srgb(0.5)]);

module cut_torus() {
    difference() {
        torus(R = 2, r = 1);
        translate([-4, -4, 0.2]) cube([8, 4, 1.8]);
    }
}

if (flat) {
    material(color = [srgb(0.2), srgb(0.2), srgb(0.2)], ambient = 1, diffuse = 0, specular = 0)
        halfspace([0, 0, 1], -1);
    material(color = [1, 1, 1], ambient = 1, diffuse = 0, specular = 0) cut_torus();
} else {
    material(color = [srgb(0.1), srgb(0.1), srgb(0.1)], color2 = [1, 1, 1], pattern = "checker",
             scale = 1, ambient = 0.1, diffuse = 0.8, specular = 0)
        halfspace([0, 0, 1], -1);
    // finish { ambient 0 diffuse 0.05 specular 0.6 roughness 0.01 reflection 0.05 }
    material(color = [srgb(0.95), srgb(0.95), 1], ambient = 0, diffuse = 0.05, specular = 0.6,
             shininess = 100, reflect = 0.05, transmit = 0.9, ior = 1.5)
        cut_torus();
}
