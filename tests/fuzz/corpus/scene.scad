camera(eye = [10, -10, 8], center = [0, 0, 0], up = [0, 0, 1], fov = 40, projection = "perspective");
light(position = [5, 5, 10], color = [1, 1, 1], intensity = 0.8, shadows = true);
light([-5, 0, 5], "white", 0.3, false);
background([0.1, 0.1, 0.2]);
material(color = "gold", ambient = 0.1, diffuse = 0.6, specular = 0.4, shininess = 50,
         reflect = 0.2, transmit = 0.0, ior = 1.5) sphere(2);
material(transmit = 0.8, ior = 1.33) translate([4, 0, 0]) cube(2, center = true);
