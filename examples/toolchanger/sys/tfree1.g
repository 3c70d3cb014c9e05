; tfree1.g
; called when tool 1 (right carriage) is freed

if move.axes[3].homed && move.axes[2].homed
  G91
  G1 Z1 F600                         ; small lift so the nozzle does not drag over the print
  G90
  G1 U{global.parkU} F{global.wipeSpeed}   ; park the right carriage
