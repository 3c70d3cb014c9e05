; The card of tests/lsp_features_test.py (hover, completion, signature help). Its lines are found by their text.
M584 X0 Y1 Z2 U3 E4
M308 S1 P"e0temp" Y"thermistor"
M950 H1 C"e0heat" T1
M950 F0 C"fan0"
global bedTemp = 60
M563 P0 S"Düse 😀 links" D0 H1 F0 ; rrflint: disable=tool-redefined,RRF320
M563 P1 S"Right" D0 H1 X3 F0
G10 P1 X-0.35 Y0.2 Z0
M98 P"tools.g"
M1234 P1
G10 P1 U0 Y0 Z0
M563 P1 S"Again" D0 H1 X3 F0 ; tool 1 again
