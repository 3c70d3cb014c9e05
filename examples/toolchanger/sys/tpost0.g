; tpost0.g
; called after tool 0 (left carriage) has been selected

M116 P0                              ; wait for the left hotend to reach its set temperatures
G1 X-30 F9000                        ; pass the nozzle over the wiper brush at the left end
