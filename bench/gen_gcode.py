#!/usr/bin/env python3
"""Write a large, realistic RepRapFirmware config-style G-code file for benchmarks.

The output looks like a long config.g mixed with macros: comment headers, drive and axis setup (M569, M584,
M350, M92, M906, M208, M574), heaters (M308, M950, M307, M143), tools (M563 and G10 for tools 0-49), G1 moves,
and meta-command blocks (if/elif/else, while, var, set, global, echo) holding expressions and quoted strings.

The syntax is valid for RRF 3.5: quotes and braces are balanced, blocks are indented with two spaces only,
no comment sits at column 0 inside a block, every `set` names a variable in scope, `break` only appears in a
loop, and every line is shorter than 200 characters. The same --seed and --size always give the same bytes.

    python3 bench/gen_gcode.py --size 10M --out /tmp/x.g
    python3 bench/gen_gcode.py --size 1M --seed 7 --out - | head

Sizes: a number of bytes with an optional K, M or G suffix (powers of 1024). The file has exactly that size.
Only the standard library is used.
"""

import argparse
import random
import re
import sys

CHUNK_BYTES = 4 << 20  # write in pieces of about this size
INDENT = "  "
MAX_DEPTH = 3


def parse_size(text):
    m = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*([kKmMgG]?)(?:i?[bB])?\s*", text)
    if not m:
        raise argparse.ArgumentTypeError(f"bad size '{text}' (examples: 500K, 10M, 1G)")
    scale = {"": 1, "k": 1 << 10, "m": 1 << 20, "g": 1 << 30}[m.group(2).lower()]
    size = int(float(m.group(1)) * scale)
    if size < 1:
        raise argparse.ArgumentTypeError("size must be at least one byte")
    return size


class Generator:
    """Produces complete top-level units (sections or blocks) as lists of lines without newlines."""

    def __init__(self, seed):
        rng = random.Random(seed)
        self.rng = rng
        self.r = rng.random
        self.ri = rng.randrange
        self.pick = rng.choice
        self.var_serial = 0
        self.unit_serial = 0
        self.tool = 0
        self.heater = 1

        # Pools of formatted numbers: formatting floats is the slow part, so do it once.
        def pool(n, fn):
            return [fn() for _ in range(n)]

        self.xs = pool(4096, lambda: f"{rng.uniform(-20, 320):.3f}")
        self.ys = pool(4096, lambda: f"{rng.uniform(0, 300):.3f}")
        self.zs = pool(1024, lambda: f"{rng.uniform(0.2, 280):.2f}")
        self.es = pool(2048, lambda: f"{rng.uniform(-1.5, 2.5):.5f}")
        self.fs = pool(64, lambda: str(rng.choice([600, 1200, 1800, 2400, 3000, 4800, 6000, 9000, 12000])))
        self.offs = pool(512, lambda: f"{rng.uniform(-2, 2):.2f}")
        self.temps = pool(128, lambda: str(rng.randrange(150, 280, 5)))
        self.small = pool(256, lambda: f"{rng.uniform(0, 10):.2f}")

    # ---- names and small pieces -------------------------------------------------------------------

    def new_var(self):
        self.var_serial += 1
        return self.pick(VAR_BASES) + "_" + str(self.var_serial)

    def expr(self, scope):
        """A numeric expression (without braces)."""
        p = self.ri(10)
        if scope and p < 4:
            v = "var." + self.pick(scope)
            return self.pick([v, v + " + " + self.pick(self.small), v + " * 2", "max(" + v + ", 0)",
                              "floor(" + v + " / 3)", "(" + v + " - 1) * 0.5"])
        if p < 7:
            return self.pick(OM_NUMBERS)
        if p < 9:
            return self.pick(OM_NUMBERS) + " " + self.pick(["+", "-", "*"]) + " " + self.pick(self.small)
        return "min(" + self.pick(OM_NUMBERS) + ", " + self.pick(self.small) + ")"

    def cond(self, scope, in_loop):
        p = self.ri(10)
        if in_loop and p < 3:
            return "iterations < " + str(self.ri(2, 9))
        if scope and p < 6:
            return "var." + self.pick(scope) + " " + self.pick(["<", ">", ">=", "!=", "=="]) + " " + \
                str(self.ri(0, 50))
        if p < 8:
            return self.pick(OM_CONDITIONS)
        return self.pick(OM_CONDITIONS) + " " + self.pick(["&&", "||"]) + " " + self.pick(OM_CONDITIONS)

    def eol(self, line, prob=0.3):
        if self.r() < prob:
            return line + "   ; " + self.pick(EOL_COMMENTS)
        return line

    # ---- simple lines -----------------------------------------------------------------------------

    def move_line(self, scope):
        r = self.r()
        pick = self.pick
        if r < 0.55:
            line = "G1 X" + pick(self.xs) + " Y" + pick(self.ys) + " E" + pick(self.es)
        elif r < 0.75:
            line = "G1 X" + pick(self.xs) + " Y" + pick(self.ys) + " F" + pick(self.fs)
        elif r < 0.85:
            line = "G1 Z" + pick(self.zs) + " F" + pick(self.fs)
        elif r < 0.93:
            line = "G1 E" + pick(self.es) + " F" + pick(self.fs)
        else:
            line = "G1 X{" + self.expr(scope) + "} Y" + pick(self.ys) + " F" + pick(self.fs)
        if self.r() < 0.08:
            return line + "   ; " + self.pick(MOVE_COMMENTS)
        return line

    def misc_line(self, scope):
        t = self.ri(50)
        pick = self.pick
        k = self.ri(14)
        if k == 0:
            return "M106 P" + str(self.ri(4)) + " S" + f"{self.r():.2f}"
        if k == 1:
            return "M568 P" + str(t) + " S" + pick(self.temps) + " R" + pick(self.temps) + " A2"
        if k == 2:
            return "M116 P" + str(t)
        if k == 3:
            return "M140 S" + str(self.ri(50, 110, 5))
        if k == 4:
            return "G4 S" + str(self.ri(1, 5))
        if k == 5:
            return "M400"
        if k == 6:
            return 'M291 P"' + pick(MESSAGES) + '" R"' + pick(TITLES) + '" S' + str(self.ri(1, 4))
        if k == 7:
            return 'M117 "' + pick(MESSAGES) + '"'
        if k == 8:
            return "G1 X{" + self.expr(scope) + "} Y{" + self.expr(scope) + "} F" + pick(self.fs)
        if k == 9:
            return "M204 P" + str(self.ri(500, 5000, 100)) + " T" + str(self.ri(1000, 10000, 100))
        if k == 10:
            return "M220 S" + str(self.ri(50, 150))
        if k == 11:
            return "G92 E0"
        if k == 12:
            return "M83"
        return "G90"

    def echo_line(self, scope):
        p = self.ri(5)
        if p == 0:
            return 'echo "' + self.pick(MESSAGES) + '"'
        if p == 1 and scope:
            return 'echo "' + self.pick(LABELS) + ' = ", var.' + self.pick(scope)
        if p == 2:
            return 'echo "' + self.pick(LABELS) + ': " ^ ' + self.pick(OM_NUMBERS)
        if p == 3:
            return 'echo >>"' + self.pick(LOGS) + '" "' + self.pick(MESSAGES) + '", state.upTime'
        return 'echo "' + self.pick(LABELS) + '", ' + self.expr(scope) + ', "' + self.pick(UNITS) + '"'

    def simple_lines(self, scope, in_loop, out, ind):
        """Append one to a few ordinary lines (may declare a var into scope)."""
        r = self.r()
        if r < 0.45:
            for _ in range(self.ri(1, 8)):
                out.append(ind + self.move_line(scope))
        elif r < 0.62:
            out.append(ind + self.eol(self.misc_line(scope)))
        elif r < 0.74:
            out.append(ind + self.echo_line(scope))
        elif r < 0.84:
            name = self.new_var()
            init, numeric = self.var_init(scope)
            out.append(ind + "var " + name + " = " + init)
            if numeric:  # only numeric variables are used in later arithmetic
                scope.append(name)
        elif r < 0.93 and scope:
            v = self.pick(scope)
            out.append(ind + "set var." + v + " = " + self.expr(scope))
        elif in_loop and r < 0.96:
            out.append(ind + "if " + self.cond(scope, True))
            out.append(ind + INDENT + self.pick(["break", "continue"]))
        else:
            # An indented comment line counts as empty, so follow it with code: blocks must not be empty.
            out.append(ind + "; " + self.pick(EOL_COMMENTS))
            out.append(ind + self.misc_line(scope))

    def var_init(self, scope):
        """The initial value of a new variable, and whether it is a number."""
        p = self.ri(6)
        if p == 0:
            return '"' + self.pick(LABELS) + '"', False
        if p == 1:
            return self.pick(["true", "false"]), False
        if p == 2:
            return "{" + self.pick(self.small) + ", " + self.pick(self.small) + "}", False
        return self.expr(scope), True

    # ---- blocks -------------------------------------------------------------------------------------

    def block(self, depth, scope, in_loop, out):
        """An if/elif/else chain or a while loop at the given depth."""
        ind = INDENT * depth
        if self.r() < 0.35:
            if scope and self.r() < 0.3:
                cond = "var." + self.pick(scope) + " < " + str(self.ri(5, 60))
            elif self.r() < 0.85:
                cond = "iterations < " + str(self.ri(2, 12))
            else:
                cond = self.cond(scope, True)
            out.append(ind + "while " + cond)
            self.body(depth + 1, scope, True, out)
            return
        out.append(ind + "if " + self.cond(scope, in_loop))
        self.body(depth + 1, scope, in_loop, out)
        for _ in range(self.ri(3) if self.r() < 0.3 else 0):
            out.append(ind + "elif " + self.cond(scope, in_loop))
            self.body(depth + 1, scope, in_loop, out)
        if self.r() < 0.45:
            out.append(ind + "else")
            self.body(depth + 1, scope, in_loop, out)

    def body(self, depth, scope, in_loop, out):
        inner = list(scope)  # vars declared in the block are local to it
        ind = INDENT * depth
        for _ in range(self.ri(1, 6)):
            if depth < MAX_DEPTH and self.r() < 0.18:
                self.block(depth, inner, in_loop, out)
            else:
                self.simple_lines(inner, in_loop, out, ind)

    # ---- config sections ------------------------------------------------------------------------------

    def drives_section(self, out):
        rng = self.ri
        out.append("; Drives")
        for d in range(rng(4, 7)):
            out.append(self.eol(f"M569 P0.{d} S{rng(2)}", 0.8))
        e = "0.4:0.5" if rng(2) else f"{rng(20, 24)}.0:{rng(24, 28)}.0"
        out.append(f"M584 X0.0 Y0.1 Z0.2:0.3 U0.6 E{e}   ; set drive mapping")
        out.append("M350 X16 Y16 Z16 U16 E16:16 I1   ; microstepping with interpolation")
        xy = self.pick(["80.00", "100.00", "160.00"])
        out.append(f"M92 X{xy} Y{xy} Z{self.pick(['400.00', '800.00', '1600.00'])} U{xy} E{rng(380, 840)}.00:"
                   f"{rng(380, 840)}.00   ; steps per mm")
        out.append(f"M566 X{rng(6, 12)}00.00 Y{rng(6, 12)}00.00 Z60.00 U{rng(6, 12)}00.00 E300.00:300.00 P1")
        out.append(f"M203 X{rng(10, 20)}000.00 Y{rng(10, 20)}000.00 Z900.00 U{rng(10, 20)}000.00 E3600.00:3600.00")
        out.append(f"M201 X{rng(10, 40)}00.00 Y{rng(10, 40)}00.00 Z100.00 U{rng(10, 40)}00.00 E2500.00:2500.00")
        out.append(f"M906 X{rng(8, 15)}00 Y{rng(8, 15)}00 Z{rng(6, 12)}00 U{rng(8, 15)}00 E{rng(4, 9)}00:"
                   f"{rng(4, 9)}00 I30   ; motor currents (mA)")
        out.append("M84 S30")
        out.append(f"M208 X-{rng(0, 40)}:{rng(250, 350)} Y0:{rng(250, 350)} Z0:{rng(200, 400)} U{rng(0, 20)}:{rng(320, 380)}")
        out.append('M574 X1 S1 P"io0.in"')
        out.append('M574 U2 S1 P"io1.in"')
        out.append('M574 Y' + str(rng(1, 3)) + ' S1 P"!io2.in"')
        out.append("M574 Z1 S2")

    def heater_section(self, out):
        h = self.heater
        self.heater = h + 1 if h < 30 else 1
        pin = h % 4
        kind = self.ri(3)
        if kind == 0:
            out.append(f'M308 S{h} P"temp{pin}" Y"thermistor" T100000 B{self.pick([3950, 4138, 4725])} A"Heater {h}"')
        elif kind == 1:
            out.append(f'M308 S{h} P"temp{pin}" Y"pt1000" A"Nozzle {h}"')
        else:
            out.append(f'M308 S{h} P"{20 + h % 8}.temp0" Y"thermistor" T100000 B4725 C7.06e-8 A"Tool board {h}"')
        out.append(self.eol(f'M950 H{h} C"out{1 + h % 3}" T{h}', 0.7))
        out.append(f"M307 H{h} R{self.pick(self.small)} K0.{self.ri(100, 999)}:0.{self.ri(0, 999):03d} "
                   f"D{self.pick(self.small)} E1.35 S1.00 B0 V24.0")
        out.append(f"M143 H{h} S{self.ri(260, 320, 5)}")
        if self.r() < 0.5:
            f = h % 8
            out.append(f'M950 F{f} C"out{4 + f % 6}" Q500')
            out.append(f"M106 P{f} S1 H{h} T45")

    def tool_section(self, out):
        t = self.tool
        self.tool = (t + 1) % 50
        h = 1 + t % 30
        if t % 2:
            out.append(f'M563 P{t} S"Tool {t} right" D1 H{h} X3 F2   ; X moves drive the U carriage')
            out.append(f"G10 P{t} U{self.pick(self.offs)} Y{self.pick(self.offs)} Z{self.pick(self.offs)}")
        else:
            out.append(f'M563 P{t} S"Tool {t}" D0 H{h} F0')
            out.append(f"G10 P{t} X{self.pick(self.offs)} Y{self.pick(self.offs)} Z{self.pick(self.offs)}")
        if self.r() < 0.4:
            out.append(f"M568 P{t} R{self.pick(self.temps)} S{self.pick(self.temps)} A0")

    def globals_section(self, out):
        g = self.pick(GLOBALS)
        out.append(f"if !exists(global.{g})")
        out.append(f"  global {g} = {self.pick(self.small)}")
        out.append(f"set global.{g} = global.{g} + 1")

    # ---- top level --------------------------------------------------------------------------------------

    def unit(self, scope, out):
        r = self.r()
        self.unit_serial += 1
        if r < 0.30:
            for _ in range(self.ri(4, 40)):
                out.append(self.move_line(scope))
        elif r < 0.42:
            self.block(0, scope, False, out)
        elif r < 0.52:
            out.append("")
            out.append("; " + self.pick(SECTION_TITLES) + " (" + str(self.unit_serial) + ")")
            out.append("; " + self.pick(PROSE))
        elif r < 0.60:
            self.drives_section(out)
        elif r < 0.70:
            self.heater_section(out)
        elif r < 0.82:
            self.tool_section(out)
        elif r < 0.86:
            self.globals_section(out)
        else:
            # Top-level vars stay in scope for the rest of the file; keep only a few of them visible.
            self.simple_lines(scope, False, out, "")
            if len(scope) > 12:
                del scope[:-8]

    def chunks(self, size):
        """Yield byte strings whose lengths add up to exactly size."""
        header = [
            "; Benchmark input generated by bench/gen_gcode.py",
            "; Configuration file for Duet 3 MB6HC (firmware version 3.5)",
            "G90",
            "M83",
            'M550 P"bench"',
        ]
        for g in GLOBALS:  # declared up front so that every later global.* reference is defined
            header += ["if !exists(global." + g + ")", "  global " + g + " = " + self.pick(self.small)]
        header = ("\n".join(header) + "\n").encode()
        written = 0
        if len(header) > size:
            header = b""
        yield header
        written += len(header)
        scope = []
        while written < size:
            lines = []
            for _ in range(2000):
                self.unit(scope, lines)
            lines.append("")
            data = "\n".join(lines).encode()
            if written + len(data) <= size:
                yield data
                written += len(data)
                continue
            # Keep whole top-level units only, then pad with column-0 comments to the exact size.
            # A cut is safe where the next line starts a new top-level unit (column 0, not else/elif).
            cut = data.rfind(b"\n", 0, size - written)
            while cut >= 0 and data[cut + 1:cut + 2] in (b" ", b"e"):
                cut = data.rfind(b"\n", 0, cut)
            data = data[:cut + 1] if cut >= 0 else b""
            yield data
            written += len(data)
            yield padding(size - written)
            written = size


def padding(n):
    """n bytes of comment lines (or a lone newline)."""
    out = []
    while n > 0:
        if n == 1:
            out.append("\n")
            break
        take = min(n, 80)
        if n - take == 1:
            take -= 1
        out.append(";" + "." * (take - 2) + "\n" if take >= 2 else "\n")
        n -= take
    return "".join(out).encode()


VAR_BASES = ["count", "speed", "offset", "target", "layer", "tries", "pos", "temp", "probe", "delta", "limit",
             "step", "wait", "dwell", "height", "radius", "index", "ok", "label", "ratio"]
GLOBALS = ["purgeLength", "parkX", "parkU", "wipeSpeed", "filamentType", "lastTool", "bedTemp", "zOffset",
           "chamberTarget", "retries"]
OM_NUMBERS = ["move.axes[0].max", "move.axes[1].max", "move.axes[2].userPosition", "move.axes[0].machinePosition",
              "heat.heaters[0].current", "heat.heaters[1].active", "heat.heaters[2].standby", "state.upTime",
              "sensors.probes[0].value[0]", "tools[0].offsets[2]", "move.extruders[0].factor",
              "fans[0].actualValue", "job.layer", "move.speedFactor", "global.purgeLength", "state.currentTool",
              "#tools", "boards[0].vIn.current", "move.axes[3].min", "sensors.analog[1].lastReading"]
OM_CONDITIONS = ["move.axes[0].homed", "!move.axes[1].homed", "move.axes[2].homed", "state.currentTool == 0",
                 "state.currentTool < 0", "heat.heaters[1].current > 170", "exists(global.parkX)",
                 "!exists(global.zOffset)", "job.file.fileName != null", "sensors.filamentMonitors[0].status == \"ok\"",
                 "state.status == \"processing\"", "fans[1].requestedValue > 0.5", "move.axes[3].homed",
                 "boards[0].vIn.current < 22.5"]
EOL_COMMENTS = ["wait for temperatures", "purge a little", "prime the nozzle", "park the carriage",
                "tuned 2024", "TODO check this value", "from the calibration print", "changed after the upgrade",
                "see the wiki", "keep in sync with the slicer", "do not change", "measured value"]
MOVE_COMMENTS = ["wipe", "purge line", "travel", "prime", "retract", "lift Z", "back to the print",
                 "move to the wipe position", "slow approach", "perimeter", "infill", "outer wall"]
SECTION_TITLES = ["Drives", "Axis Limits", "Endstops", "Z-Probe", "Heaters", "Fans", "Tools", "Miscellaneous",
                  "Custom settings", "Filament", "Purge and wipe", "Network", "General preferences"]
PROSE = ["values below were measured on the real machine", "change these together with the slicer profile",
         "keep this section in sync with homeall.g", "generated by RepRapFirmware Configuration Tool v3.5",
         "see the Duet3D documentation for the meaning of each parameter", "do not move above the tool section"]
MESSAGES = ["Heating done", "Loading filament", "Unloading filament", "Probe triggered too early",
            "Press OK to continue", "Insert the probe pin", "Tool change complete", "Bed levelled",
            'Press ""OK"" when the nozzle is clean', "Layer done", "Purging", "Calibration finished"]
TITLES = ["Filament", "Probe", "Tool change", "Calibration", "Warning"]
LABELS = ["Tool", "Offset", "Speed", "Layer", "Temperature", "Height", "Count", "Position", "Voltage"]
UNITS = ["mm", "mm/s", "C", "s", "%"]
LOGS = ["/sys/bench-log.txt", "0:/sys/events.log", "toolchange.log"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=parse_size, default=parse_size("10M"), help="output size, e.g. 1M, 10M, 100M")
    ap.add_argument("--out", required=True, help="output file, or - for stdout")
    ap.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    args = ap.parse_args()

    gen = Generator(args.seed)
    sink = sys.stdout.buffer if args.out == "-" else open(args.out, "wb")
    try:
        buf, buffered = [], 0
        for data in gen.chunks(args.size):
            buf.append(data)
            buffered += len(data)
            if buffered >= CHUNK_BYTES:
                sink.write(b"".join(buf))
                buf, buffered = [], 0
        sink.write(b"".join(buf))
    except BrokenPipeError:
        pass
    finally:
        if sink is not sys.stdout.buffer:
            sink.close()


if __name__ == "__main__":
    main()
