evens = [for (i = [0:10]) if (i % 2 == 0) i];
pairs = [for (i = [0:2]) for (j = [0:1]) [i, j]];
flat = [for (v = [[1, 2], [3]]) each v];
cstyle = [for (i = 0, s = 1; i < 5; i = i + 1, s = s * 2) s];
lets = [for (i = [1:3]) let (sq = i * i) if (sq > 2) sq else -sq];
echo(evens, pairs, flat, cstyle, lets, [each [1:3], each "ab"]);
