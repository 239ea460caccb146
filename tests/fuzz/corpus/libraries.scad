// What BOSL2 and MCAD need of the language (issue 25): C-style for with empty parts and a
// sequential update, each over comprehensions, function values printed as source, ranges
// indexed and compared, $parent_modules / parent_module(), lexical $children, duplicate
// parameters, is_undef of unknown names, snapped inverse trigonometry, unknown modules.
l = [[[1, 2]]];
s = [for (; is_list(l) && len(l) > 0; l = l[0]) len(l)];
c = [for (i = 0, j = 0; i < 5; i = i + 1, j = i, k = j) [i, j, k]];
e = [each for (i = [0:3]) [i, [i]], each let(a = "ab") a, each if (true) [0:2], each undef];
f = function(x, y = [1, "q\"", undef]) let(z = -x) assert(z < 0) echo(z) [for (i = [0:x]) if (i % 2) i else -i, each [x:2:9]];
g = function(h) h(1)(2) + (function(q) q)(3)[0].x;
echo(s, c, e, f, str(g), [f, g], f(3), len(str(f, f, f)));
r = [0:2:9];
echo(r[0], r[1], r[2], r[3], r[-1], r == [0:2:8], [0:0/0:1] == [5:1:3], [1:"a"], is_undef(nothing));
echo(acos(-0.5), asin(0.5), atan(1), atan2(1, sqrt(3)), sin(45), cos(45), tan(30), tan(90), tan(-180));
module a() { echo($parent_modules, parent_module(), parent_module(0), parent_module(-1), parent_module(9), parent_module(0/0), parent_module(1, 2)); children(); }
module b(x = parent_module(0)) a() echo(x, $children, $parent_modules);
b() cube();
module d(r, r = 2, r) echo(r);
d(); d(1); d(r = 3); d(1, 2, 3);
not_a_module(1) sphere(1);
function p(n) = n <= 0 ? function() n : p(n - 1);
echo(p(100));
$fn = 8;
rotate_extrude() polygon([[0, 0], [3, 0], [3, 0]]);
