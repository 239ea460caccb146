a = 1; b = -2.5e-3; c = 0x10; t = true; f = false; u = undef; s = "tab\t\"q\" \x41 \u263A";
v = [1, [2, 3], "x", undef]; r = [0:2:10]; r2 = [5:1]; e = [];
echo(a, b, c, t, f, u, s, v, r, r2, e, v[1][0], v.x, s[2], r.begin, r.step, r.end);
