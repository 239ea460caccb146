// line comment
/* block
   comment */ cube(1); /**/ sphere(1); // trailing
