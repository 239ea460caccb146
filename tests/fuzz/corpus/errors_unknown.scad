foo(); x = bar(1); echo(nope); linear_extrude(2) square(1);
