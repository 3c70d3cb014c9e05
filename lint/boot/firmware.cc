#include "lint/boot/firmware.h"

#include <algorithm>
#include <vector>

#include <fmt/format.h>
#include <cctype>

namespace rrflint {

std::string Version::str() const {
  std::string s = fmt::format("{}.{}", major, minor);
  if (major < 3) s = fmt::format("{}.{:02}", major, minor);
  if (patch) s += fmt::format(".{}", patch);
  static constexpr const char* kStage[] = {"alpha", "beta", "rc", ""};
  if (stage < kRelease) s += fmt::format("-{}.{}", kStage[stage], pre_num);
  return s;
}

std::optional<Version> Version::parse(std::string_view s) {
  auto num = [&](size_t& i, uint32_t& out) {
    size_t b = i;
    out = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])) && i - b < 5)
      out = out * 10 + uint32_t(s[i++] - '0');
    return i > b;
  };
  size_t i = 0;
  if (i < s.size() && (s[i] == 'v' || s[i] == 'V')) ++i;
  uint32_t ma = 0, mi = 0, pa = 0;
  if (!num(i, ma)) return std::nullopt;
  if (i < s.size() && s[i] == '.') {
    ++i;
    size_t b = i;
    if (!num(i, mi)) return std::nullopt;
    // RRF 2 writes "2.05": two digits are the minor version 5; "3.01" likewise is 3.1 (3.01-RC3 era).
    (void)b;
  }
  if (i < s.size() && s[i] == '.') {
    ++i;
    if (!num(i, pa)) return std::nullopt;
  }
  Version v(static_cast<uint16_t>(ma), static_cast<uint16_t>(mi), static_cast<uint16_t>(pa));
  if (i < s.size()) {
    std::string rest;
    for (size_t k = i; k < s.size(); ++k) rest += static_cast<char>(std::tolower(static_cast<unsigned char>(s[k])));
    size_t k = 0;
    while (k < rest.size() && (rest[k] == '-' || rest[k] == '.' || rest[k] == '_' || rest[k] == '+')) ++k;
    uint8_t st = kRelease;
    if (rest.compare(k, 5, "alpha") == 0) st = kAlpha, k += 5;
    else if (rest.compare(k, 4, "beta") == 0) st = kBeta, k += 4;
    else if (rest.compare(k, 2, "rc") == 0) st = kRc, k += 2;
    else if (rest.compare(k, 1, "a") == 0) st = kAlpha, k += 1;
    else if (rest.compare(k, 1, "b") == 0) st = kBeta, k += 1;
    else return std::nullopt;
    while (k < rest.size() && (rest[k] == '.' || rest[k] == '-')) ++k;
    uint32_t pn = 0;
    size_t b = k;
    while (k < rest.size() && std::isdigit(static_cast<unsigned char>(rest[k])))
      pn = pn * 10 + uint32_t(rest[k++] - '0');
    if (k != rest.size() || (k == b && false)) return std::nullopt;
    v.stage = st;
    v.pre_num = static_cast<uint8_t>(pn > 255 ? 255 : pn);
  }
  if (v.major == 0 || v.major > 9) return std::nullopt;
  return v;
}

std::string_view board_name(Board b) {
  switch (b) {
    case Board::Duet2: return "duet2";
    case Board::Duet3_6HC: return "duet3-6hc";
    case Board::Duet3_Mini: return "duet3-mini";
    case Board::Maestro: return "maestro";
    case Board::Unknown: break;
  }
  return "unknown";
}

std::optional<Board> parse_board(std::string_view s) {
  std::string l;
  for (char c : s)
    if (c != ' ' && c != '_') l += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (l == "duet2" || l == "duet2wifi" || l == "duet2ethernet" || l == "duetwifi" || l == "duetethernet")
    return Board::Duet2;
  if (l == "duet3-6hc" || l == "duet3" || l == "6hc" || l == "mb6hc" || l == "6xd" || l == "duet3-6xd" || l == "mb6xd")
    return Board::Duet3_6HC;
  if (l == "duet3-mini" || l == "mini5+" || l == "mini" || l == "duet3mini") return Board::Duet3_Mini;
  if (l == "maestro" || l == "duet2maestro") return Board::Maestro;
  if (l == "unknown" || l == "auto") return Board::Unknown;
  return std::nullopt;
}

BoardLimits board_limits(Board b, Version v) {
  const bool v35 = v >= kRrf3_5, v33 = v >= kRrf3_3, v31 = v >= kRrf3_1;
  switch (b) {
    case Board::Duet3_6HC:
      if (v35) return {30, 20, 32};
      if (v33) return {15, 16, 25};
      return {10, 16, 20};
    case Board::Duet3_Mini:
      if (v >= kRrf3_4) return {10, 8, 12};
      if (v33) return {10, 5, 12};
      return {8, 5, 8};
    case Board::Duet2:
      if (v31) return {10, 7, 12};
      return {9, 6, 12};
    case Board::Maestro: return {6, 4, 7};
    case Board::Unknown: break;
  }
  if (v35) return {30, 20, 32};
  if (v33) return {15, 16, 25};
  return {10, 16, 20};
}

int max_line_length(Version v) {
  if (v >= kRrf3_4) return 255;
  if (v >= kRrf3_1) return 200;
  return 160;
}

namespace {

struct CodeRange {
  char letter;
  int number;
  int fraction;
  int first, last;
};

constexpr CodeRange kCodes[] = {
#define CODE(l, n, f, a, b) {l, n, f, a, b},
#include "lint/boot/command_table.inc"
#undef CODE
};

// The versions (bit per version index) that implement each code, looked up per command rather than searched.
struct CodeIndex {
  static constexpr int kNumbers = 1024, kFractions = 11;  // fraction -1..9
  std::vector<uint8_t> versions = std::vector<uint8_t>(2 * kNumbers * kFractions, 0);
  CodeIndex() {
    for (const CodeRange& c : kCodes)
      if (c.number >= 0 && c.number < kNumbers && c.fraction >= -1 && c.fraction <= 9)
        for (int v = c.first; v <= c.last; ++v) versions[slot(c.letter, c.number, c.fraction)] |= uint8_t(1u << v);
  }
  static size_t slot(char letter, int number, int fraction) {
    return (static_cast<size_t>(letter == 'M') * kNumbers + static_cast<size_t>(number)) * kFractions +
           static_cast<size_t>(fraction + 1);
  }
};

}  // namespace

int code_version_index(Version v) {
  if (v.major < 3) return 0;
  if (v.minor >= 6 || v.major > 3) return kCodeVersions - 1;
  return 1 + v.minor;
}

Version code_index_version(int i) {
  constexpr Version kByIndex[kCodeVersions] = {Version(2, 5, 1), Version(3, 0, 0), Version(3, 1, 1), Version(3, 2, 2),
                                               Version(3, 3, 0), Version(3, 4, 6), Version(3, 5, 4), kLatestVersion};
  return kByIndex[std::clamp(i, 0, kCodeVersions - 1)];
}

uint8_t code_versions(char letter, int number, int fraction) {
  static const CodeIndex index;
  if (number < 0 || number >= CodeIndex::kNumbers || fraction < -1 || fraction > 9) return 0;
  return index.versions[CodeIndex::slot(letter, number, fraction)];
}

bool cr_is_not_a_line_end(Version v) {
  if (v.major == 3 && v.minor == 4) return v >= Version(3, 4, 6);
  return v >= kRrf3_5_0_beta2;
}

int max_stack_depth(Version v) {
  if (v >= kRrf3_4) return 10;
  if (v >= kRrf3_1) return 7;
  return 5;
}

char highest_lowercase_axis(Board b, Version v) {
  if (v < kRrf3_3) return 0;
  if (v < kRrf3_5) return 'l';
  return (b == Board::Duet3_6HC || b == Board::Unknown) ? 'z' : 'f';
}

int default_extruders(Version v) { return v >= kRrf3_3 ? 0 : 1; }

}  // namespace rrflint

namespace rrflint {

std::string known_versions() {
  return fmt::format("1.x, 2.0x, 3.0 to {}.{}, written as 3.5, 3.4.6, 3.5.0beta2, 3.5.0-beta.2, 3.01-RC3 or 2.02RC2",
                     kLatestVersion.major, kLatestVersion.minor);
}

std::optional<Version> parse_target_version(std::string_view text, std::string* warning, std::string* error) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  auto v = Version::parse(text);
  if (!v || v->major < 1) {
    if (error) *error = fmt::format("'{}' is not a firmware version rrflint knows (known: {})", text, known_versions());
    return std::nullopt;
  }
  if (*v > kLatestVersion) {
    if (warning)
      *warning = fmt::format("firmware {} is newer than the newest version rrflint knows ({}): linted as {}", text,
                             kLatestVersion.str(), kLatestVersion.str());
    return kLatestVersion;
  }
  return v;
}

}  // namespace rrflint
