function add(a, b = 2) = a + b;
function fact(n) = n <= 1 ? 1 : n * fact(n - 1);
function sum(n, acc = 0) = n == 0 ? acc : sum(n - 1, acc + n);
sq = function (x) x * x;
compose = function (f, g) function (x) f(g(x));
echo(add(1), add(1, 3), add(b = 5, a = 1), fact(10), sum(1000), sq(4), compose(sq, sq)(3));
echo(is_function(sq), is_undef(undef), is_num(1), is_bool(true), is_string("s"), is_list([]));
