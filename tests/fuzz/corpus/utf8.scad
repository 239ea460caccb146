s = "ünïcödé ☃ 𝄞"; echo(len(s), s[1], str(s, s));
