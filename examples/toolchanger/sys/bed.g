; bed.g
; called by G32: probe the mesh and enable bed compensation

M561                                 ; drop any existing bed transform
if !move.axes[0].homed || !move.axes[1].homed || !move.axes[2].homed || !move.axes[3].homed
  G28                                ; home everything first

G1 U{global.parkU} F{global.wipeSpeed}   ; right carriage out of the way
G1 Z5 F600
G1 X178 Y150 F9000                   ; probe over the bed centre
G30                                  ; refresh the Z datum
G29 S0                               ; probe the grid from M557, save heightmap.csv and load it
