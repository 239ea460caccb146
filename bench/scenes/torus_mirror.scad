// The peer benchmark ../shared/peers/torus_mirror.pov in csgray's language: the seed thesis'
// torus (R = 2, r = 1) with a mirror finish over a plane. POV <x, y, z> is [x, z, y] here (see
// csg_grid.scad), so POV's torus in its xz plane is csgray's torus around the z axis.
//
// The checker: POV's is 3-D, colour 1 where floor(x) + floor(y) + floor(z) is even, with y
// nudged up by a tolerance so the plane y = -1 reads floor(y) = -1. On the plane that is
// white where floor(x) + floor(z) is odd; csgray's 2-D checker on the plane's x-y frame gives
// color where floor(x) + floor(y) is even and color2 where odd, so color2 is the white. POV's
// max_trace_level 5 is --max-depth 4 (the primary ray is POV's level 1), which
// bench/peer_render.sh passes. Lighting models differ (POV's specular and roughness are not
// Blinn-Phong's weight and exponent), so shades differ; the silhouettes are the comparison.
//
// -D flat=true: the plane and the torus in flat colours (linear 0.2 and 1), no reflection,
// on black, for the silhouette comparison.
flat = false;

function srgb(x) = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;

camera(eye = [0, -9, 6], center = [0, 0, 0], up = [0, 0, 1], fov = 45);
light([10, -10, 20]);
background(flat ? [0, 0, 0] : [srgb(0.2), srgb(0.3), srgb(0.5)]);

if (flat) {
    material(color = [srgb(0.2), srgb(0.2), srgb(0.2)], ambient = 1, diffuse = 0, specular = 0)
        halfspace([0, 0, 1], -1);
    material(color = [1, 1, 1], ambient = 1, diffuse = 0, specular = 0) torus(R = 2, r = 1);
} else {
    material(color = [srgb(0.1), srgb(0.1), srgb(0.1)], color2 = [1, 1, 1], pattern = "checker",
             scale = 1, ambient = 0.1, diffuse = 0.8, specular = 0)
        halfspace([0, 0, 1], -1);
    // finish { ambient 0.05 diffuse 0.2 specular 0.8 roughness 0.01 reflection 0.7 }
    material(color = [srgb(0.9), srgb(0.9), srgb(0.9)], ambient = 0.05, diffuse = 0.2,
             specular = 0.8, shininess = 100, reflect = 0.7)
        torus(R = 2, r = 1);
}
