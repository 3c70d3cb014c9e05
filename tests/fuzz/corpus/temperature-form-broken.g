M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P{pa@am.T} S200 ; a G10 that does not parse: no M568 may copy it
