; The card of tests/lsp_test.py. Its findings: RRF104 inside the string after non-ASCII text (UTF-16 columns),
; RRF320 with two notes, RRF301 for tool 1 (created by an unsaved edit to tools.g); tpost0.g: RRF301 for tool 2.
M584 X0 Y1 Z2 E3
M308 S1 P"e0temp" Y"thermistor"
M950 H1 C"e0heat" T1
M563 P0 S"Düse 😀 don't" D0 H1 ; tool 0
G10 P0 X5 Y0 Z0
M563 P0 S"again" D0 H1
M98 P"tools.g"
G10 P1 X0 Y0 Z0
