; homey.g
; called to home the Y axis

G91                                  ; relative positioning
G1 H2 Z5 F600                        ; raise the bed clearance a little before moving
G1 H1 Y-310 F3600                    ; fast move towards the Y endstop
G1 H2 Y5 F6000                       ; back off
G1 H1 Y-10 F300                      ; second, slow approach
G1 H2 Z-5 F600                       ; undo the Z lift
G90                                  ; absolute positioning
