; A G10 with a line number and a matching checksum: RRF331's 'Z0' appended to it broke the checksum, and RRF would
; have dropped the whole line silently.
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
N10 G10 P0 X1 Y1*104
