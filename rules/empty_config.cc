// RRF508 empty-config: a config.g that holds no command, so the board boots with none of the machine's settings.
#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF508",
    .name = "empty-config",
    .severity = Severity::Error,
    .summary = "config.g holds no command: the board boots with none of the machine's settings.",
    .docs = R"md(
## What it does
Reports the `config.g` the board boots from (`sys/config.g`, or `sys/config.g.bak` when there is no config.g) when
it holds no command at all: no G, M or T code, no meta command (`if`, `global`, `echo`…), not even a line RRF
would reject. An empty file, blank lines and comments are all it has. The finding sits at its start.

It does not look at other files: an empty macro (a `pause.g` or `tfree0.g` left empty on purpose) does nothing,
which is what it is meant to do, and a config.g that only runs another file (`M98 P"config-main.g"`) is not empty.

## Why is this bad?
RRF runs `config.g` at power-up; it falls back to `config.g.bak` only when config.g does not exist. An empty
config.g exists, so RRF runs it, reports nothing, and the board comes up with its built-in defaults: no drivers
mapped to your axes, no steps per mm, no endstops, heaters, fans, tools, probe or network settings of yours. On a
Duet with WiFi or Ethernet and no `M552` the web interface may not come up at all, so the only way back is USB.

Such a file is most often the trace of an upload that failed or was cut short, or of a config.g commented out
while testing and written back by mistake: worth finding before the SD card goes into the board, not after.

## Example
```gcode
; config.g for the Voron 2.4
; (the upload stopped here)
```

## Use instead
```gcode
; config.g for the Voron 2.4
M550 P"voron"
M552 S1
M584 X0.0 Y0.1 Z0.2:0.3:0.4:0.5 E0.6
```

## Fix safety
There is no fix: the file's content is what is missing.

## References
- rrflint: [System files](../firmware-behaviour.md#system-files)
- RepRapFirmware 3.5: [RepRap.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Platform/RepRap.cpp)
  (`RepRap::Init()`: config.g, else config.g.bak; `RunStartupFile()`)
)md",
};

void check(const EndContext& cx, Sink& out) {
  for (const Segment& seg : cx.graph.segments) {
    if (!seg.boot) continue;
    const FileUnit& u = cx.machine.unit(seg.unit);
    if (file_role(u.sd_path) != FileRole::Config) return;
    for (const Line& l : u.parsed.lines)
      if (l.kind != LineKind::Blank && l.kind != LineKind::Comment) return;
    const SourceFile& src = *u.source;
    const std::string_view name = std::string_view(u.sd_path).substr(u.sd_path.rfind('/') + 1);
    out.report(kMeta, Location{src.id(), Span{0, 0}},
               fmt::format("{} holds no command{}: RRF runs it at power-up and the board starts with its built-in "
                           "defaults, none of this machine's drivers, axes, heaters, fans, tools or network settings",
                           name, src.size() == 0 ? " (the file is empty)" : ", only comments and blank lines"));
    return;
  }
}

}  // namespace

extern const Rule empty_config{.meta = kMeta, .check_end = check};

}  // namespace rrflint
