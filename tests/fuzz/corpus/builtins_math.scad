echo(sin(30), cos(60), tan(45), asin(0.5), acos(0.5), atan(1), atan2(1, 1));
echo(sqrt(2), pow(2, 10), exp(1), ln(10), log(100), log(2, 8), abs(-3), sign(-2));
echo(floor(1.5), ceil(1.5), round(2.5), round(-2.5), min(3, 1, 2), max([4, 9, 2]));
echo(norm([3, 4]), cross([1, 0, 0], [0, 1, 0]), len([1, 2]), len("abc"), concat([1], 2, [3, 4]));
echo(lookup(1.5, [[0, 0], [1, 10], [2, 20]]), rands(0, 1, 3, 42), PI, version(), version_num());
