; homeu.g
; called to home the U axis (right carriage)

G91                                  ; relative positioning
G1 H2 Z5 F600                        ; raise the bed clearance a little before moving
G1 H1 U340 F3600                     ; fast move towards the U endstop at the high end
G1 H2 U-5 F6000                      ; back off
G1 H1 U10 F300                       ; second, slow approach
G1 H2 Z-5 F600                       ; undo the Z lift
G90                                  ; absolute positioning
