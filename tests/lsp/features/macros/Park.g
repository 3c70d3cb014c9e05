G1 X0 Y0
G10 P1 Y0 ; run after the boot
