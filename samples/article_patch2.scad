// Article patch 2 of 3 (ruled quadratic), after "Ray tracing polynomial patches using Groebner
// bases": ruled between two quadratic curves: degree 2 in u, 1 in v. The eliminant in u has degree 4.
// The article's own control points are not in the text available to us; this patch is of the
// same kind, built in monomial form with dyadic coefficients and degree-elevated exactly to
// bicubic (tests/PatchReference.h, articlePatch(2)), so its higher coefficients are exact
// zeros up to rounding, which the small-value rule (tol::kGroebnerSmallRel) removes.
// Rendered by the thesis' method: -D 'method="resultant"' (or "clip", "newton") picks another.
// Control points row by row: P[4 i + j], i along u, j along v (primitives/patch/BezierPatch.h).
method = "groebner";
camera(eye = [-0.6, -1.3, 3.0], center = [0.7, 0.75, 0.15], up = [0, 0, 1], fov = 42);
light(position = [4, -3, 6], intensity = 1);
light(position = [-3, -4, 2], intensity = 0.4, shadows = false);
background([0.93, 0.94, 0.96]);
material(color = [0.85, 0.45, 0.2], specular = 0.3, shininess = 32)
bezier_patch(points = [
    [0, 0, 0], [1/48, 1/3, -1/24], [1/24, 2/3, -1/12], [1/16, 1, -1/8],
    [1/3, 1/24, 1/12], [55/144, 1/3, 1/8], [31/72, 5/8, 1/6], [23/48, 11/12, 5/24],
    [7/12, 1/4, -1/24], [101/144, 19/36, 5/36], [59/72, 29/36, 23/72], [15/16, 13/12, 1/2],
    [3/4, 5/8, -3/8], [47/48, 11/12, 0], [29/24, 29/24, 3/8], [23/16, 3/2, 3/4]
], method = method);
