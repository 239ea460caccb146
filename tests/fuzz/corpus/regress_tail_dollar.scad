$y = 1;
function g(n, acc = 0) = n <= 0 ? acc : g(n - 1, acc + $y + $z);
echo(g(1000000));
