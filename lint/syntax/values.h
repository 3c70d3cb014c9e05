// Reading parameter values the way RRF reads them (docs/firmware-behaviour.md#numbers-and-lists, #strings), from
// spans, on demand.
//
// A value is Absent (letter not given), Unknown (an expression: `{…}`, `param.X`), Known, or Bad (RRF would
// reject it). Rules never fire on Unknown values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lint/syntax/parser.h"

namespace rrflint {

enum class VState : uint8_t { Absent, Unknown, Known, Bad };

template <class T>
struct Val {
  VState state = VState::Absent;
  T value{};
  ParamRef param;  // the parameter read (none when absent)
  bool known() const { return state == VState::Known; }
  bool absent() const { return state == VState::Absent; }
  bool present() const { return state != VState::Absent; }
  bool unknown() const { return state == VState::Unknown; }
};

struct DriverId {
  uint16_t board = 0;
  uint16_t driver = 0;
  bool explicit_board = false;  // written as b.n
  friend bool operator==(DriverId a, DriverId b) { return a.board == b.board && a.driver == b.driver; }
  std::string str() const;
};

/// RRF's float reading: sign, digits, one '.', exponent; `80E420` overflows to +inf like SafeStrtof.
Val<double> get_float(const ParsedFile& pf, const Command& c, char letter);
/// Integer reading stops at '.' or any non-digit (`P0.5` -> 0, `Z2E3` -> 2), like StrToI32.
Val<int64_t> get_int(const ParsedFile& pf, const Command& c, char letter);
/// Quoted string contents with RRF's `""` and `'x` rules applied; unquoted text taken raw.
Val<std::string> get_string(const ParsedFile& pf, const Command& c, char letter);
/// Colon lists. The list ends at a blank before ':' (RRF stops there). An expression item makes it Unknown.
Val<std::vector<double>> get_float_list(const ParsedFile& pf, const Command& c, char letter);
Val<std::vector<int64_t>> get_int_list(const ParsedFile& pf, const Command& c, char letter);
Val<std::vector<DriverId>> get_driver_list(const ParsedFile& pf, const Command& c, char letter);

/// The items of a list parameter as spans, following RRF's rule that a blank before ':' ends the list.
std::vector<Span> list_items(const ParsedFile& pf, const Param& p);

/// Is a string parameter's value unknown here? (An expression; a quoted string is text even with braces.)
inline bool is_unknown_string(const Param& p) {
  return p.kind == ValueKind::Expression || (p.kind != ValueKind::String && p.has_expr);
}
/// Is this parameter value an expression or does it contain one?
inline bool is_unknown_value(const Param& p) { return p.has_expr || p.kind == ValueKind::Expression; }

/// Decodes an RRF quoted string body ("" -> ", 'x -> lowercase x).
std::string unquote(std::string_view quoted);

}  // namespace rrflint
