M584 X0 Y1 Z2 E3
M563 P0 D0 H1
G10 P0 X{global.xoff Y0 ; a ; cuts the expression}
