#!/usr/bin/env python3
"""A findings-heavy machine file: a block of motion and device commands (M350/M906/M92, two M584s that change the
mapping, M950/M143 for one heater, M558/G31, M671/M669) repeated N times. It exercises the look-backs and
look-aheads of the order rules (RRF203/RRF213 walk back from each M584, RRF210 ahead from each M671, RRF214 back
from each M143, RRF207 ahead from each M950 H … T), which a clean generated file never reaches: a superlinear cost
shows as time growing faster than the input. usage: gen_devices.py OUT REPEATS
"""
import sys

BLOCK = ('M350 X32 Y32 E16 I1\nM906 X800 Y800 E500\nM92 X80 Y80 E400\nM584 X0 Y1 Z2 E3\nM584 X1.0 Y1.1 U5\n'
         'M950 H1 C"out1" T1\nM143 H1 S280\nM558 P5 C"io3.in" H5\nG31 Z1.5\nM671 X0:100 Y0:0\nM669 K1\n')

if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    with open(sys.argv[1], "w") as f:
        f.write(BLOCK * int(sys.argv[2]))
