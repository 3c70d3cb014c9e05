; A tool with X and Y swapped and an offset on each letter on lines of their own: RRF304 offered to rename X to Y
; and Y to X, which undid each other at every --fix round (fuzz_fix, 2026-12-05T13:16Z).
M584 X0 Y1 Z2 E3:4
M563 P0 D0 H1 F0
M563 P1 D1 H2 F2 X1 Y0
G10 P1 X-0.42 Z0
G10 P1 Y0.15 Z0
