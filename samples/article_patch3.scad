// Article patch 3 of 3 (ruled cubic), after "Ray tracing polynomial patches using Groebner
// bases": ruled between two cubic curves: degree 3 in u, 1 in v. The eliminant in u has degree 6.
// The article's own control points are not in the text available to us; this patch is of the
// same kind, built in monomial form with dyadic coefficients and degree-elevated exactly to
// bicubic (tests/PatchReference.h, articlePatch(3)), so its higher coefficients are exact
// zeros up to rounding, which the small-value rule (tol::kGroebnerSmallRel) removes.
// Rendered by the thesis' method: -D 'method="resultant"' (or "clip", "newton") picks another.
// Control points row by row: P[4 i + j], i along u, j along v (primitives/patch/BezierPatch.h).
method = "groebner";
camera(eye = [-0.7, -1.2, 4.0], center = [0.9, 0.9, 0.55], up = [0, 0, 1], fov = 42);
light(position = [4, -3, 6], intensity = 1);
light(position = [-3, -4, 2], intensity = 0.4, shadows = false);
background([0.93, 0.94, 0.96]);
material(color = [0.85, 0.45, 0.2], specular = 0.3, shininess = 32)
bezier_patch(points = [
    [0, 0, 0], [1/48, 1/3, -1/24], [1/24, 2/3, -1/12], [1/16, 1, -1/8],
    [1/3, 1/24, 1/12], [55/144, 1/3, 1/8], [31/72, 5/8, 1/6], [23/48, 11/12, 5/24],
    [7/12, 1/4, -1/24], [101/144, 19/36, 5/36], [59/72, 29/36, 23/72], [15/16, 13/12, 1/2],
    [5/4, 3/8, 1/2], [23/16, 7/8, 3/4], [13/8, 11/8, 1], [29/16, 15/8, 5/4]
], method = method);
