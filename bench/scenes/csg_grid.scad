// The peer benchmark ../shared/peers/csg_grid.pov in csgray's language: 1000 CSG parts, each
// (box ∩ sphere) − three cylinders, on a 10 x 10 x 10 grid, each turned differently.
//
// POV-Ray is left-handed with y up; csgray (OpenSCAD) is right-handed with z up. Swapping y
// and z maps one onto the other: POV <x, y, z> is [x, z, y] here. A POV rotation
// rotate <a, b, c> (x, then y, then z) becomes, under the swap, rotations by -a about x,
// then -b about z, then -c about y. POV colours are linear (assumed_gamma 1.0); csgray's are
// sRGB, so they are converted with srgb() below.
//
// -D flat=true renders every part in its own flat colour (ambient only, black background):
// linear RGB = ((i+1)/10, (j+1)/10, (k+1)/10), for the silhouette comparison with POV-Ray.
flat = false;

function srgb(x) = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;

camera(eye = [14, -22, 12], center = [4.5, 4.5, 4.5], up = [0, 0, 1], fov = 40);
light([30, -30, 40]);
background(flat ? [0, 0, 0] : [srgb(0.1), srgb(0.1), srgb(0.15)]);

module part() {
    difference() {
        intersection() {
            cube(1, center = true);
            sphere(0.68);
        }
        rotate([0, 90, 0]) cylinder(h = 2, r = 0.3, center = true);
        rotate([90, 0, 0]) cylinder(h = 2, r = 0.3, center = true);
        cylinder(h = 2, r = 0.3, center = true);
    }
}

for (i = [0:9], j = [0:9], k = [0:9])
    translate([i, k, j]) rotate([0, -k * 7, 0]) rotate([0, 0, -j * 17]) rotate([-i * 13, 0, 0])
        if (flat)
            material(color = [srgb((i + 1) / 10), srgb((j + 1) / 10), srgb((k + 1) / 10)],
                     ambient = 1, diffuse = 0, specular = 0)
                part();
        else
            // POV's finish { ambient 0.1 diffuse 0.7 specular 0.4 roughness 0.02 }: its
            // specular exponent is 1 / roughness.
            material(color = [srgb(0.8), srgb(0.3), srgb(0.2)], ambient = 0.1, diffuse = 0.7,
                     specular = 0.4, shininess = 50)
                part();
