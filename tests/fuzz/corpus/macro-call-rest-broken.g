M584 X0 Y1 Z2 E3
; rrflint: disable-next-line = unknown-command, syntax-error
M98 P"m.g" M9command was40 Y41.62s,
M98 P"m.g" M106 P0 S{1+
M98 P"m.g" M400 ; the fix moves only this one
