M584 X0 Y1 Z2:3 E4
M569 P0.2:0.3 S1 C"driver
M569 P0:1 S{1 ; note
M569 P2:3 S1   ; the fix writes one M569 per driver here only
