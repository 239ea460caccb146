include <missing.scad>
use <also_missing.scad>
cube(1);
