; homez.g
; called to home the Z axis with the probe on the left carriage

if !move.axes[0].homed || !move.axes[1].homed || !move.axes[3].homed
  abort "Home X, Y and U before homing Z"

G91                                  ; relative positioning
G1 H2 Z5 F600                        ; lift so the probe clears the bed
G90                                  ; absolute positioning
G1 U{global.parkU} F{global.wipeSpeed}   ; keep the right carriage parked
G1 X178 Y150 F9000                   ; probe (28 mm left of the nozzle) over the bed centre
G30                                  ; probe the bed and set the Z datum
G1 Z5 F600                           ; move clear of the bed
