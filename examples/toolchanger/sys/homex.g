; homex.g
; called to home the X axis (left carriage)

G91                                  ; relative positioning
G1 H2 Z5 F600                        ; raise the bed clearance a little before moving
G1 H1 X-340 F3600                    ; fast move towards the X endstop, stop when it triggers
G1 H2 X5 F6000                       ; back off
G1 H1 X-10 F300                      ; second, slow approach
G1 H2 Z-5 F600                       ; undo the Z lift
G90                                  ; absolute positioning
