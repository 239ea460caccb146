// Article patch 1 of 3 (bilinear), after "Ray tracing polynomial patches using Groebner
// bases": a twisted quadrilateral: degree 1 in u and in v. A line meets it at most twice: the eliminant in u has degree 2.
// The article's own control points are not in the text available to us; this patch is of the
// same kind, built in monomial form with dyadic coefficients and degree-elevated exactly to
// bicubic (tests/PatchReference.h, articlePatch(1)), so its higher coefficients are exact
// zeros up to rounding, which the small-value rule (tol::kGroebnerSmallRel) removes.
// Rendered by the thesis' method: -D 'method="resultant"' (or "clip", "newton") picks another.
// Control points row by row: P[4 i + j], i along u, j along v (primitives/patch/BezierPatch.h).
method = "groebner";
camera(eye = [-0.6, -1.4, 3.0], center = [0.65, 0.5, 0.35], up = [0, 0, 1], fov = 40);
light(position = [4, -3, 6], intensity = 1);
light(position = [-3, -4, 2], intensity = 0.4, shadows = false);
background([0.93, 0.94, 0.96]);
material(color = [0.85, 0.45, 0.2], specular = 0.3, shininess = 32)
bezier_patch(points = [
    [0, 0, 0], [1/48, 1/3, -1/24], [1/24, 2/3, -1/12], [1/16, 1, -1/8],
    [1/3, 1/24, 1/12], [55/144, 1/3, 1/8], [31/72, 5/8, 1/6], [23/48, 11/12, 5/24],
    [2/3, 1/12, 1/6], [107/144, 1/3, 7/24], [59/72, 7/12, 5/12], [43/48, 5/6, 13/24],
    [1, 1/8, 1/4], [53/48, 1/3, 11/24], [29/24, 13/24, 2/3], [21/16, 3/4, 7/8]
], method = method);
