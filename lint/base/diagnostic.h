// Diagnostics, notes and fixes: spans plus messages; positions are resolved only when rendering.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lint/base/source.h"

namespace rrflint {

enum class Severity : uint8_t { Info = 0, Warning = 1, Error = 2 };
std::string_view severity_name(Severity s);
std::optional<Severity> parse_severity(std::string_view s);

struct Location {
  FileId file = kNoFile;
  Span span;
};

struct Note {
  Location loc;
  std::string message;
};

/// One replacement: an empty span inserts, an empty replacement deletes.
struct Edit {
  Location loc;
  std::string replacement;
};

enum class Applicability : uint8_t {
  Safe,    // keeps what the config means; applied by --fix
  Unsafe,  // may change behaviour (intended, but check); applied with --unsafe-fixes
};
std::string_view applicability_name(Applicability a);

struct Fix {
  std::string title;  // says what the edit does: "append 'Z0'"
  Applicability applicability = Applicability::Safe;
  std::vector<Edit> edits;
};

struct Diagnostic {
  std::string_view code;  // "RRF301"
  std::string_view name;  // "g10-tool-before-definition"
  Severity severity = Severity::Warning;
  Location loc;
  std::string message;
  std::vector<Note> notes;
  std::optional<Fix> fix;
};

}  // namespace rrflint
