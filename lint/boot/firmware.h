// Firmware target: version, board and the limits that depend on them (docs/firmware-behaviour.md#firmware-versions,
// #board-limits).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rrflint {

/// An RRF version such as 3.4.6 or 3.5.0-beta.2. Pre-releases sort before the release.
struct Version {
  uint16_t major = 3, minor = 6, patch = 0;
  // 0 = alpha, 1 = beta, 2 = rc, 3 = release; `pre_num` is the pre-release number.
  uint8_t stage = 3;
  uint8_t pre_num = 0;

  constexpr Version() = default;
  constexpr Version(uint16_t ma, uint16_t mi, uint16_t pa = 0, uint8_t st = 3, uint8_t pn = 0)
      : major(ma), minor(mi), patch(pa), stage(st), pre_num(pn) {}
  constexpr auto key() const {
    return (uint64_t(major) << 40) | (uint64_t(minor) << 28) | (uint64_t(patch) << 16) | (uint64_t(stage) << 8) |
           pre_num;
  }
  friend constexpr bool operator==(Version a, Version b) { return a.key() == b.key(); }
  friend constexpr bool operator<(Version a, Version b) { return a.key() < b.key(); }
  friend constexpr bool operator<=(Version a, Version b) { return a.key() <= b.key(); }
  friend constexpr bool operator>(Version a, Version b) { return a.key() > b.key(); }
  friend constexpr bool operator>=(Version a, Version b) { return a.key() >= b.key(); }

  std::string str() const;
  /// Parses "3", "3.5", "3.4.6", "3.5.0beta2", "3.6.0-beta.3", "2.05.1", "3.01-RC3". Nullopt if malformed.
  static std::optional<Version> parse(std::string_view s);
};

/// The newest version rrflint knows; the default target when nothing says otherwise.
inline constexpr Version kLatestVersion{3, 6, 0};

enum class Board : uint8_t { Unknown, Duet2, Duet3_6HC, Duet3_Mini, Maestro };
std::string_view board_name(Board b);
std::optional<Board> parse_board(std::string_view s);

struct BoardLimits {
  int max_axes;
  int max_extruders;
  int max_axes_plus_extruders;
};
/// MaxAxes / MaxExtruders / MaxAxesPlusExtruders (docs/firmware-behaviour.md#board-limits). Unknown board: the most permissive.
BoardLimits board_limits(Board b, Version v);

/// Stored line limit: 255 from 3.4, 200 for 3.1–3.3, 160 before.
int max_line_length(Version v);
/// Macro nesting limit MaxStackDepth: 10 from 3.4, 7 for 3.01–3.3, 5 before.
int max_stack_depth(Version v);
/// Highest lowercase axis letter: none before 3.3, 'l' in 3.3/3.4, 'f' or 'z' (6HC/6XD) from 3.5.
char highest_lowercase_axis(Board b, Version v);
/// Extruders that exist before any M584 E: 0 from 3.3, 1 in 3.0–3.2.
int default_extruders(Version v);
/// Does a lone CR fail to end a line in a file? From 3.4.6 on the 3.4 line and from 3.5.0-beta.2, RRF discards CR
/// when it reads a file, so a file with CR-only line endings is one line.
bool cr_is_not_a_line_end(Version v);

/// A firmware target as users write it (`--firmware`, `firmware =` in .rrflint.toml): "3.5", "3.4.6", "3.5.0beta2",
/// "3.5.0-beta.2", "3.01-RC3", "2.02RC2". A version newer than kLatestVersion is taken as kLatestVersion, with a
/// `warning`; text that is not a version, or a version older than 1.0, gives nullopt and an `error` that lists the
/// known versions.
std::optional<Version> parse_target_version(std::string_view text, std::string* warning, std::string* error);
/// The firmware versions rrflint knows, for messages: "1.x, 2.0x, 3.0 to 3.6".
std::string known_versions();

}  // namespace rrflint
