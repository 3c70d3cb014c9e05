; CNC mode, and a G10 whose '(' comment runs to the end of the line: RRF331's 'Z0' was appended inside the comment
; and came back every --fix round (fuzz_fix, 2026-12-05T13:52Z).
M453
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
G10 P0 X0 Y0 (left tool
