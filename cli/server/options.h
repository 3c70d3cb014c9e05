// The language server's settings from the editor: `initializationOptions` of initialize and the `settings` of
// workspace/didChangeConfiguration (either the object itself or its `rrflint` member).
//
//   { "firmware": "3.5", "select": ["RRF3"], "ignore": ["RRF104", "line-too-long"], "debounce": 150 }
//
// `firmware`, `select` and `ignore` are checked as the command-line options are (cli::check_options) and become
// the base settings beneath `.rrflint.toml` (cli::CliOptions::base_firmware, base_selection): a config file's value
// wins where both set one. `debounce` is the quiet time in milliseconds before a didChange is linted (0 to 10000).
// A key that is absent or null keeps its default; unknown keys are ignored.
#pragma once

#include <chrono>
#include <string>

#include "cli/cli.h"
#include "cli/server/protocol.h"

namespace rrflint::server {

inline constexpr std::chrono::milliseconds kDefaultDebounce{150};
inline constexpr int kMaxDebounceMs = 10000;

struct ServerOptions {
  cli::CliOptions cli;  // the base_ settings set, the rest at the command line's defaults
  std::chrono::milliseconds debounce = kDefaultDebounce;
};

/// Reads the editor's settings (`settings` unwrapped from its `rrflint` member when it has one). False with `err`
/// on a bad value (`out` is then unchanged); `warn` gets what to tell the user anyway.
bool read_options(const json& settings, ServerOptions& out, std::string& err, std::string& warn);

}  // namespace rrflint::server
