for (i = [0:1e6]) for (j = [0:1e6]) cube(1);
function f(n) = n <= 0 ? 1 : f(n - 1) + f(n - 1);
echo(f(60));
