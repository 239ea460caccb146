a = 1; echo(a); a = 2;
$s = 10;
module show() echo($s = $s, a = a);
module wrap() { $s = 20; show(); }
wrap(); show();
function g() = $s;
echo(g(), let($s = 5) g());
