function f(n, acc) = n == 0 ? acc : f(n - 1, [acc]);
x = f(100000, []);
echo(x == x);
