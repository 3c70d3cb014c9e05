M563 P1 S"L" D0 H1
G10 P1 X1"Y0 Z0   ; an unterminated string: Z0 appended after it joins the string
