; Configuration file for Duet 3 MB6HC (firmware version 3.5)
; executed by the firmware on start-up
;
; "Twinhead": 300 x 300 mm IDEX printer, two independent carriages on one X beam.
; Left carriage = X axis (tool 0), right carriage = U axis (tool 1).

; General preferences
G90                                              ; absolute coordinates
M83                                              ; relative extruder moves
M550 P"Twinhead"                                 ; printer name
M98 P"globals.g"                                 ; shared settings used by the tool and park macros

; Network
M552 P0.0.0.0 S1                                 ; Ethernet on, address from DHCP
M586 P0 S1                                       ; HTTP on
M586 P1 S0                                       ; FTP off
M586 P2 S0                                       ; Telnet off

; Drives
M569 P0.0 S1                                     ; driver 0.0: left carriage (X), forwards
M569 P0.1 S0                                     ; driver 0.1: Y, backwards
M569 P0.2 S1                                     ; driver 0.2: Z, forwards
M569 P0.3 S0                                     ; driver 0.3: right carriage (U), backwards
M569 P0.4 S1                                     ; driver 0.4: left extruder, forwards
M569 P0.5 S0                                     ; driver 0.5: right extruder, backwards
M584 X0.0 Y0.1 Z0.2 E0.4:0.5                     ; map the motion axes and both extruders
M350 X16 Y16 Z16 E16:16 I1                       ; x16 microstepping with interpolation
M92 X100.00 Y100.00 Z400.00 U100.00 E409.00:409.00 ; steps per mm (16 tooth pulleys, 8 mm lead screw)
M584 U0.3                                        ; second X carriage runs as the U axis
M350 U16 I1                                      ; same microstepping for the right carriage
M566 X900.00 Y600.00 Z30.00 U900.00 E300.00:300.00 P1      ; maximum instantaneous speed changes (mm/min)
M203 X15000.00 Y12000.00 Z600.00 U15000.00 E3600.00:3600.00 ; maximum speeds (mm/min)
M201 X3000.00 Y2000.00 Z100.00 U3000.00 E2500.00:2500.00    ; accelerations (mm/s^2)
M906 X1200 Y1400 Z1000 U1200 E700:700 I30        ; motor currents (mA) and idle factor (%)
M84 S30                                          ; idle timeout (s)

; Axis limits
M208 X-35:290 Y0:300 Z0:300 U10:335              ; travel of each axis, parking bays included

; Endstops
M574 X1 S1 P"io0.in"                             ; left carriage homes to the low end
M574 U2 S1 P"io1.in"                             ; right carriage homes to the high end
M574 Y1 S1 P"io2.in"                             ; Y homes to the low end
M574 Z1 S2                                       ; Z homes with the probe

; Z probe (inductive sensor on the left carriage)
M558 P5 C"^io3.in" H5 F300 T9000 A3 S0.02        ; digital probe, dive 5 mm, up to 3 probes per point
G31 P500 X-28 Y0 Z1.45                           ; probe offset from the left nozzle and trigger height
M557 X15:255 Y15:285 S30                         ; mesh grid

; Bed heater
M308 S0 P"temp0" Y"thermistor" T100000 B3950 A"Bed"   ; sensor 0: bed thermistor
M950 H0 C"out0" T0                               ; heater 0 on out0, read by sensor 0
M307 H0 R0.412 K0.301:0.000 D5.18 E1.35 S1.00 B0 ; bed heater model
M140 H0                                          ; heater 0 is the bed heater
M143 H0 S120                                     ; bed over-temperature limit

; Tools
M563 P0 S"Left" D0 H1 F0                         ; tool 0: left carriage, extruder 0, heater 1, part fan 0
G10 P0 X0 Y0 Z0                                  ; tool 0 is the reference nozzle
G10 P1 U0 Y0 Z0                                  ; clear the offsets of tool 1
M563 P1 S"Right" D1 H2 X3 F2                     ; tool 1: right carriage, X moves drive axis 3 (U)

; Left hotend
M308 S1 P"temp1" Y"thermistor" T100000 B4725 A"Left nozzle"   ; sensor 1: left hotend thermistor
M950 H1 C"out1" T1                               ; heater 1 on out1, read by sensor 1
M307 H1 R2.512 K0.471:0.165 D5.42 E1.35 S1.00 B0 V24.0        ; left heater model

; Right hotend (PT1000 for high temperature filaments)
M308 S2 P"temp2" Y"pt1000" A"Right nozzle"       ; sensor 2: right hotend PT1000
M950 H2 C"out2" T2                               ; heater 2 on out2, read by sensor 2
M307 H2 R2.487 K0.462:0.171 D5.60 E1.35 S1.00 B0 V24.0        ; right heater model
M143 H2 S300                                     ; right hotend over-temperature limit

; Fans
M950 F0 C"out4" Q500                             ; fan 0: left part cooling
M106 P0 C"Part L" S0 H-1                         ; off until the slicer asks for it
M950 F1 C"out7" Q500                             ; fan 1: left heat sink
M106 P1 S1 H1 T45                                ; thermostatic, on above 45 C
M950 F2 C"out5" Q500                             ; fan 2: right part cooling
M106 P2 C"Part R" S0 H-1                         ; off until the slicer asks for it
M950 F3 C"out8" Q500                             ; fan 3: right heat sink
M106 P3 S1 H2 T45                                ; thermostatic, on above 45 C

; Board monitoring and lights
M308 S10 Y"mcu-temp" A"MCU"                      ; sensor 10: processor temperature
M308 S11 Y"drivers" A"Drivers"                   ; sensor 11: stepper driver temperature warnings
M950 F4 C"out9" Q500                             ; fan 4: electronics bay fan
M106 P4 C"Electronics" S0.4 H10:11 T40:70        ; speeds up with the processor or driver temperature
M950 P0 C"out6" Q500                             ; general purpose output 0: LED strip
M42 P0 S0.6                                      ; LEDs at 60 %

; Extrusion tuning
M207 S0.8 R0 F2400 Z0.2                          ; firmware retraction for both tools
M572 D0:1 S0.045                                 ; pressure advance, both extruders
M593 P"mzv" F41.5                                ; input shaping for ringing at 41.5 Hz

; Tool offsets from the calibration print
G10 P1 X-0.35 Y0.2 Z0                            ; right nozzle relative to the left one

; Power loss
M911 S21.0 R23.0 P"M913 X0 Y0 U0 G91 M83 G1 Z3 E-5 F1000"    ; save the job and lift the head on power loss

; Miscellaneous
M501                                             ; load saved parameters (heater models, workplaces)
T0                                               ; start with the left tool
