; The card of tests/lsp_core_test.py. Its findings by default: RRF104 twice (both with a safe fix), RRF328
; (M568 before 3.3 is not ruled out), RRF307 (the deprecated G10 temperature form; its fix is safe once --firmware
; rules out 3.2), RRF116 (X81 is ignored), RRF501 (new.g is not on the card until a test writes it).
M584 X0 Y1 Z2 E3
M308 S1 P"e0temp" Y"thermistor"
M950 H1 C"e0heat" T1
M563 P0 S"it's" D0 H1
M563 P1 S"don't" D0 H1
G10 P0 X0 Y0 Z0
G10 P1 X0 Y0 Z0
M568 P0 S200 R0
G10 P0 S200 R0
M92 X80 X81
M98 P"new.g"
