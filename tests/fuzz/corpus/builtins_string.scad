echo(str("a", 1, [2, "b"], undef), chr(65), chr([72, 105]), chr(9731), ord("A"), ord("☃"));
echo(str(1 / 3), str(1e10), str(-0), str(1 / 0), str(0 / 0), "esc\\n\n");
