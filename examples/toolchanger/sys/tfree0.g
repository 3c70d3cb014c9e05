; tfree0.g
; called when tool 0 (left carriage) is freed

if move.axes[0].homed && move.axes[2].homed
  G91
  G1 Z1 F600                         ; small lift so the nozzle does not drag over the print
  G90
  G1 X{global.parkX} F{global.wipeSpeed}   ; park the left carriage
