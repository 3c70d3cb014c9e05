; sample RRF G-code for the grammar test
N10 G1 X10.5 Y-2 F{global.speed * 60} ; move
M584 X0.0:0.1 Y1 E2:3
M550 P"My ""Duet"" printer"
T-1 P0
M308 S1 P"temp0" Y"thermistor" T100000
G28 (home all) X
G53 G1 Z5 M400
if move.axes[0].homed && exists(global.speed)
  var offset = {param.S + 1.5e-1}
elif !fileexists("0:/sys/x.g")
  set global.speed = max(10, var.offset)
else
  echo >>"0:/sys/log.txt" "speed", global.speed, pi
while iterations < 3
  break
abort "stop"
global retries = 0x1F
