// Firmware target inference: which RRF version (and board) a config is written for (issue: core §4).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "lint/base/diagnostic.h"
#include "lint/boot/firmware.h"
#include "lint/card/card.h"

namespace rrflint {

struct Evidence {
  enum class Kind : uint8_t { Stated, Floor, Ceiling } kind;
  Version version;
  std::string what;  // "M950 creates devices (RRF 3.0 or later)"
  Location loc;
};

struct Target {
  Version version = kLatestVersion;
  Board board = Board::Unknown;
  bool version_given = false;  // from --firmware / config, not inferred
  bool board_given = false;
  std::vector<Evidence> evidence;
  std::string reason;  // one sentence: how the version was chosen
  std::string board_reason;
};

/// The newest release of the series a stated version belongs to (3.4 -> 3.4.6).
Version series_latest(Version v);

/// Infers the target from every parsed file of the machine; `config` is the unit of config.g if any.
Target infer_target(const Machine& m, const FileUnit* config, std::optional<Version> given,
                    std::optional<Board> given_board);

}  // namespace rrflint
