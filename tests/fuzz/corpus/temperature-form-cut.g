M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P0 X1 S{global.t ; a ; cuts the expression the M568 would take }
