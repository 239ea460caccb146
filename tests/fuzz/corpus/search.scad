echo(search("a", "abcabc"), search("a", "abcabc", 0), search("bc", "abcabc"));
echo(search(3, [1, 3, 5, 3]), search([3, 5], [1, 3, 5, 3], 0));
echo(search("b", [["a", 1], ["b", 2], ["b", 3]], 0), search([["b"]], [["a", 1], ["b", 2]], 1, 0));
