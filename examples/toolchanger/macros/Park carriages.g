; Park carriages.g
; move both carriages into their parking bays, e.g. before cleaning the bed

if !move.axes[0].homed || !move.axes[3].homed
  echo "Carriages not homed, homing X and U first"
  G28 X U

var toolBefore = state.currentTool
T-1                                  ; free the current tool (runs its tfree macro)
G1 X{global.parkX} U{global.parkU} F{global.wipeSpeed}
echo "Carriages parked, tool " ^ var.toolBefore ^ " was selected before"
