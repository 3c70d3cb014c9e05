; The card of tests/clients/ (neovim and Emacs with eglot, each driving `rrflint server`). Its findings: RRF104
; on line 7, after non-ASCII text (UTF-16 columns; the safe fix doubles the apostrophe), RRF320 on line 9;
; tools.g: RRF301 for tool 1, which is never created.
M584 X0 Y1 Z2 E3
M308 S1 P"e0temp" Y"thermistor"
M950 H1 C"e0heat" T1
M563 P0 S"Größe 😀 don't" D0 H1 ; tool 0
G10 P0 X5 Y0 Z0
M563 P0 S"again" D0 H1
M98 P"tools.g"
