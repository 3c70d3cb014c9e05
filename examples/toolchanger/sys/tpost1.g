; tpost1.g
; called after tool 1 (right carriage) has been selected

M116 P1                              ; wait for the right hotend to reach its set temperatures
if move.axes[3].homed
  G1 X330 F{global.wipeSpeed}        ; X drives the right carriage now: wipe at the right end
