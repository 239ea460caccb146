echo(rands(0, 1, 2, 1e300), rands(0, 1, 2, -1/0), rands(0, 1, 0/0), rands(0, 1, 1e300));
