// Text positions as LSP counts them, and file URIs.
//
// LSP positions are a 0-based line and a 0-based character offset in UTF-16 code units (the only encoding this
// server offers). Lines end at "\n", "\r\n" or a lone "\r", as in SourceFile. A byte that is not valid UTF-8 counts
// as one unit (as it does as one code point in the CLI's columns); a position past the end of a line is the end of
// the line, and one inside a surrogate pair is the end of that code point.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "lint/base/source.h"

namespace rrflint::server {

struct Position {
  uint32_t line = 0, character = 0;
};

/// The length of one UTF-8 sequence starting at `s[i]` (1 for an invalid byte), and its UTF-16 units in `units`.
size_t utf8_step(std::string_view s, size_t i, uint32_t& units);
/// UTF-16 units in `s`.
uint32_t utf16_length(std::string_view s);
/// UTF-16 units of `s` before byte `off`; a character `off` falls inside is counted only with `round_up` (the end
/// of a range, which then covers it).
uint32_t utf16_before(std::string_view s, size_t off, bool round_up);
/// An LSP range for a span of a file, in UTF-16 units.
nlohmann::json range_json(const SourceFile& f, Span s);
/// The byte offset of an LSP position in `text` (clamped to the line's end, or to the text's end past the last line).
size_t offset_of(std::string_view text, Position p);
/// Replaces the range [start, end) of `text` (LSP positions) with `replacement`; an end before the start is taken
/// as the start.
void apply_change(std::string& text, Position start, Position end, std::string_view replacement);

/// The file a `file://` URI names (percent-decoded, with an optional "localhost" authority); nullopt for other
/// schemes, another host or a relative path.
std::optional<std::string> path_of_uri(std::string_view uri);
/// A `file://` URI for an absolute path, percent-encoding what RFC 3986 does not allow in a path.
std::string uri_of_path(std::string_view path);

}  // namespace rrflint::server
