// linear_extrude's twist and scale arguments that are errors at the argument.
linear_extrude(1, twist = "x") square(1);
linear_extrude(1, scale = [1]) square(1);
