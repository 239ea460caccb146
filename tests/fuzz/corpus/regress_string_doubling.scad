function f(s, n) = n == 0 ? s : f(str(s, s), n - 1);
echo(len(f("ab", 40)));
