; preheat_pla.g
; heat the bed and both hotends for PLA, then wait

var nozzle = 210                     ; active temperature (C)
var standby = 170                    ; standby temperature (C)

M140 S60                             ; bed to 60 C
while iterations < 2
  M568 P{iterations} S{var.nozzle} R{var.standby} A2   ; tools 0 and 1: set temperatures, heaters on
M116                                 ; wait for everything to reach its target
if heat.heaters[0].current < 55
  echo "Bed is still below 55 C, check the heater"
else
  M291 P"PLA preheat done" R"Preheat" S1 T5
