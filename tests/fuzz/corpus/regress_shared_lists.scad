// A billion numbers that cost three thousand steps to build: printing, comparing or adding
// them must stop at the work budget.
a = [for (i = [0:999]) i]; b = [for (i = [0:999]) a]; c = [for (i = [0:999]) b];
b2 = [for (i = [0:999]) [for (j = [0:999]) j]]; c2 = [for (i = [0:999]) b2];
echo(c == c2, c < c2, len(c + c), len(str(c)), len(chr(c)));
