// Diagnostics, notes and fixes: spans plus messages; positions are resolved only when rendering.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
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

/// One replacement: an empty span inserts, an empty replacement deletes. Build one with the named constructors.
struct Edit {
  Location loc;
  std::string replacement;

  /// Inserts `text` at the start of `at` (an empty span, or what the text goes in front of).
  static Edit insert(Location at, std::string text) {
    return Edit{Location{at.file, Span{at.span.begin, at.span.begin}}, std::move(text)};
  }
  /// Deletes what `what` spans.
  static Edit remove(Location what) { return Edit{what, std::string()}; }
  /// Replaces what `what` spans with `text`.
  static Edit replace(Location what, std::string text) { return Edit{what, std::move(text)}; }
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

  /// A fix that keeps what the config means: `Fix::safe("remove the byte-order mark", Edit::remove(at))`. With no
  /// edits, add them to `edits` afterwards (one per match of a loop).
  template <class... Edits>
  static Fix safe(std::string title, Edits&&... edits) {
    return make(Applicability::Safe, std::move(title), std::forward<Edits>(edits)...);
  }
  /// A fix that may change behaviour (intended, but check).
  template <class... Edits>
  static Fix unsafe(std::string title, Edits&&... edits) {
    return make(Applicability::Unsafe, std::move(title), std::forward<Edits>(edits)...);
  }

 private:
  template <class... Edits>
  static Fix make(Applicability a, std::string title, Edits&&... edits) {
    Fix f{std::move(title), a, {}};
    f.edits.reserve(sizeof...(edits));
    (f.edits.push_back(std::forward<Edits>(edits)), ...);
    return f;
  }
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
