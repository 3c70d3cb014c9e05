; a blank before a string that never closes: no fix may remove it
M98 P "macros/leds.g    ; a comment inside the open string
M950 F0 C "out7 Q500
