; homeall.g
; called to home all axes (G28 with no letters)

G91                                  ; relative positioning
G1 H2 Z5 F600                        ; raise the bed clearance a little before moving
G1 H1 X-340 U340 Y-310 F3600         ; both carriages and Y towards their endstops
G1 H2 X5 U-5 Y5 F6000                ; back off all three
G1 H1 X-10 U10 Y-10 F300             ; second, slow approach
G90                                  ; absolute positioning

G1 X178 Y150 F9000                   ; probe over the bed centre
G30                                  ; probe the bed and set the Z datum
G1 Z5 F600                           ; move clear of the bed
