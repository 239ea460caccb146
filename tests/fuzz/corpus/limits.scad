function inf(n) = inf(n + 1) + 1;
module deep(n) deep(n + 1);
for (i = [0:1e12]) cube(1);
x = [for (i = [0:1e9]) i];
echo(inf(0));
deep(0);
