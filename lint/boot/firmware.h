// Firmware target: version, board and the limits that depend on them (docs/firmware-behaviour.md#firmware-versions,
// #board-limits).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rrflint {

/// An RRF version such as 3.4.6 or 3.5.0-beta.2. Pre-releases sort before the release.
///
/// How to write one (the five-number constructor is for the parser; code names versions as below):
/// - `Version(3, 4, 6)`: a release, here 3.4.6 itself (3.4.6-beta.1 sorts before it);
/// - `Version::first_of(3, 4)`, `first_of(3, 5, 2)`: the earliest build of 3.4.0 / 3.5.2, its first pre-release,
///   so that `v >= first_of(3, 4)` holds for every 3.4 build, alphas, betas and RCs included;
/// - `Version::alpha/beta/rc(3, 5, 0, 2)`: one pre-release, here 3.5.0-beta.2.
/// The thresholds the code compares with are named below: kRrfX_Y or kRrfX_Y_Z is `first_of` that version
/// ("needs RRF 3.4": `v >= kRrf3_4`), and a specific pre-release spells its stage: kRrf3_5_0_beta2.
struct Version {
  uint16_t major = 3, minor = 6, patch = 0;
  // kAlpha, kBeta, kRc or kRelease; `pre_num` is the pre-release number.
  uint8_t stage = 3;
  uint8_t pre_num = 0;
  static constexpr uint8_t kAlpha = 0, kBeta = 1, kRc = 2, kRelease = 3;

  constexpr Version() = default;
  constexpr Version(uint16_t ma, uint16_t mi, uint16_t pa = 0, uint8_t st = kRelease, uint8_t pn = 0)
      : major(ma), minor(mi), patch(pa), stage(st), pre_num(pn) {}
  /// The earliest build of ma.mi.pa: its first pre-release (alpha 0), before every other build of it.
  static constexpr Version first_of(uint16_t ma, uint16_t mi, uint16_t pa = 0) { return {ma, mi, pa, kAlpha, 0}; }
  static constexpr Version alpha(uint16_t ma, uint16_t mi, uint16_t pa, uint8_t n) { return {ma, mi, pa, kAlpha, n}; }
  static constexpr Version beta(uint16_t ma, uint16_t mi, uint16_t pa, uint8_t n) { return {ma, mi, pa, kBeta, n}; }
  static constexpr Version rc(uint16_t ma, uint16_t mi, uint16_t pa, uint8_t n) { return {ma, mi, pa, kRc, n}; }
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
/// The oldest version rrflint knows: the floor when no feature says otherwise.
inline constexpr Version kOldestVersion{1, 0, 0};

// The versions the code compares with (see Version): kRrfX_Y is the first build of X.Y, pre-releases included.
inline constexpr Version kRrf3_0 = Version::first_of(3, 0);
inline constexpr Version kRrf3_1 = Version::first_of(3, 1);  // RRF writes it 3.01
inline constexpr Version kRrf3_2 = Version::first_of(3, 2);
inline constexpr Version kRrf3_3 = Version::first_of(3, 3);
inline constexpr Version kRrf3_4 = Version::first_of(3, 4);
inline constexpr Version kRrf3_5 = Version::first_of(3, 5);
inline constexpr Version kRrf3_5_2 = Version::first_of(3, 5, 2);
inline constexpr Version kRrf3_5_0_beta2 = Version::beta(3, 5, 0, 2);
inline constexpr Version kRrf3_5_0_rc1 = Version::rc(3, 5, 0, 1);

enum class Board : uint8_t { Unknown, Duet2, Duet3_6HC, Duet3_Mini, Maestro };
std::string_view board_name(Board b);
std::optional<Board> parse_board(std::string_view s);

struct BoardLimits {
  int max_axes;
  int max_extruders;
  int max_axes_plus_extruders;
};
/// MaxAxes / MaxExtruders / MaxAxesPlusExtruders (docs/firmware-behaviour.md#board-limits). Unknown board: the most
/// permissive.
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

/// The versions of lint/boot/command_table.inc, by index: 0 = 2.05, 1 = 3.0, 2 = 3.1, ... 7 = 3.6.
inline constexpr int kCodeVersions = 8;
int code_version_index(Version v);
/// The newest release of the version of index `i` (0 -> 2.05.1, 4 -> 3.3.0, 7 -> the newest known).
Version code_index_version(int i);
/// The versions (bit i: index i) that implement a G or M code natively; fraction -1 is the code without one.
uint8_t code_versions(char letter, int number, int fraction);
inline bool implemented(char letter, int number, int fraction, int index) {
  return (code_versions(letter, number, fraction) >> index) & 1u;
}

/// A firmware target as users write it (`--firmware`, `firmware =` in .rrflint.toml): "3.5", "3.4.6", "3.5.0beta2",
/// "3.5.0-beta.2", "3.01-RC3", "2.02RC2". A version newer than kLatestVersion is taken as kLatestVersion, with a
/// `warning`; text that is not a version, or a version older than 1.0, gives nullopt and an `error` that lists the
/// known versions.
std::optional<Version> parse_target_version(std::string_view text, std::string* warning, std::string* error);
/// The firmware versions rrflint knows, for messages: "1.x, 2.0x, 3.0 to 3.6".
std::string known_versions();

}  // namespace rrflint
