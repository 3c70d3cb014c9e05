// Value reading (docs/firmware-behaviour.md#numbers-and-lists, #strings): get_int/get_float/get_string, lists, driver
// ids.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "lint/syntax/values.h"

using namespace rrflint;

namespace {

/// One parsed command, kept alive with its source.
struct One {
  std::unique_ptr<SourceFile> source;
  ParsedFile pf;
  Command cmd() const { return pf.commands[0]; }
};

One cmd(std::string text) {
  One o;
  o.source = std::make_unique<SourceFile>(0, "config.g", "/sys/config.g", std::move(text));
  o.pf = parse(*o.source);
  return o;
}

std::vector<std::string> items(const One& o, char letter) {
  std::vector<std::string> out;
  for (Span s : list_items(o.pf, *o.pf.find(o.cmd(), letter))) out.emplace_back(o.pf.text(s));
  return out;
}

}  // namespace

TEST_CASE("values: get_int", "[values]") {
  One o = cmd("M563 P3 D-1 H+2 S0.5 Q{1} R\"x\" F A");
  auto p = get_int(o.pf, o.cmd(), 'P');
  CHECK(p.state == VState::Known);
  CHECK(p.value == 3);
  CHECK(p.param.is(*o.pf.find(o.cmd(), 'P')));
  CHECK(get_int(o.pf, o.cmd(), 'D').value == -1);
  CHECK(get_int(o.pf, o.cmd(), 'H').value == 2);
  // Reading stops at '.': `S0.5` is 0, like StrToI32.
  CHECK(get_int(o.pf, o.cmd(), 'S').known());
  CHECK(get_int(o.pf, o.cmd(), 'S').value == 0);
  CHECK(get_int(o.pf, o.cmd(), 'Q').state == VState::Unknown);
  CHECK(get_int(o.pf, o.cmd(), 'R').state == VState::Bad);
  CHECK(get_int(o.pf, o.cmd(), 'F').state == VState::Bad);  // no value
  CHECK(get_int(o.pf, o.cmd(), 'Z').state == VState::Absent);
  CHECK(get_int(o.pf, o.cmd(), 'Z').param == nullptr);

  // An integer parameter stops at the swallowed exponent: `Z2E3` is 2 and there is no E.
  One m = cmd("M584 X0 Y1 Z2E3");
  CHECK(get_int(m.pf, m.cmd(), 'Z').value == 2);
  CHECK(get_int(m.pf, m.cmd(), 'E').absent());
  // First of duplicates.
  One d = cmd("M106 P1 P2");
  CHECK(get_int(d.pf, d.cmd(), 'P').value == 1);
}

TEST_CASE("values: get_float", "[values]") {
  One o = cmd("G1 X-3.5 Y+2 Z.25 U1e2 V80E420 W{1.5} A\"1\" B C1.5.5");
  CHECK(get_float(o.pf, o.cmd(), 'X').value == -3.5);
  CHECK(get_float(o.pf, o.cmd(), 'Y').value == 2.0);
  CHECK(get_float(o.pf, o.cmd(), 'Z').value == 0.25);
  CHECK(get_float(o.pf, o.cmd(), 'U').value == 100.0);
  // 80E420 overflows to +inf, as RRF's SafeStrtof does.
  auto v = get_float(o.pf, o.cmd(), 'V');
  CHECK(v.known());
  CHECK(std::isinf(v.value));
  CHECK(get_float(o.pf, o.cmd(), 'W').unknown());
  CHECK(get_float(o.pf, o.cmd(), 'A').state == VState::Bad);
  CHECK(get_float(o.pf, o.cmd(), 'B').state == VState::Bad);
  CHECK(get_float(o.pf, o.cmd(), 'C').value == 1.5);  // reading stops at the second '.'
  CHECK(get_float(o.pf, o.cmd(), 'D').absent());
}

TEST_CASE("values: lists end at a blank before ':'", "[values]") {
  One o = cmd("M92 X80:80.5 E420 :430 Y1: 2 Z{a}:3 U\"a:b\":{c}");
  CHECK(items(o, 'X') == std::vector<std::string>{"80", "80.5"});
  CHECK(items(o, 'E') == std::vector<std::string>{"420"});
  CHECK(items(o, 'Y') == std::vector<std::string>{"1", "2"});
  CHECK(items(o, 'Z') == std::vector<std::string>{"{a}", "3"});
  CHECK(items(o, 'U') == std::vector<std::string>{"\"a:b\"", "{c}"});

  auto x = get_float_list(o.pf, o.cmd(), 'X');
  CHECK(x.known());
  CHECK(x.value == std::vector<double>{80, 80.5});
  CHECK(get_float_list(o.pf, o.cmd(), 'E').value == std::vector<double>{420});
  CHECK(get_float_list(o.pf, o.cmd(), 'Z').unknown());
  CHECK(get_int_list(o.pf, o.cmd(), 'Y').value == std::vector<int64_t>{1, 2});
  // A single number is a list of one.
  One one = cmd("M563 P0 D3 H1:2 F{0}");
  CHECK(get_int_list(one.pf, one.cmd(), 'D').value == std::vector<int64_t>{3});
  CHECK(get_int_list(one.pf, one.cmd(), 'H').value == std::vector<int64_t>{1, 2});
  CHECK(get_int_list(one.pf, one.cmd(), 'F').unknown());
  CHECK(get_int_list(one.pf, one.cmd(), 'X').absent());
  One bad = cmd("M563 P0 D1:x S\"a\"");
  CHECK(get_int_list(bad.pf, bad.cmd(), 'D').state == VState::Bad);
  CHECK(get_int_list(bad.pf, bad.cmd(), 'S').state == VState::Bad);
}

TEST_CASE("values: driver ids", "[values]") {
  One o = cmd("M584 X0.1 Y21.0:22.3 Z2 E1.10 U{0.4} V1.");
  auto x = get_driver_list(o.pf, o.cmd(), 'X');
  REQUIRE(x.known());
  REQUIRE(x.value.size() == 1);
  CHECK(x.value[0].board == 0);
  CHECK(x.value[0].driver == 1);
  CHECK(x.value[0].explicit_board);
  CHECK(x.value[0].str() == "0.1");
  auto y = get_driver_list(o.pf, o.cmd(), 'Y');
  CHECK(y.value == std::vector<DriverId>{{21, 0}, {22, 3}});
  auto z = get_driver_list(o.pf, o.cmd(), 'Z');
  CHECK(z.value[0].driver == 2);
  CHECK_FALSE(z.value[0].explicit_board);
  CHECK(z.value[0].str() == "2");
  // `1.10` is board 1, driver 10 (not 1.1).
  auto e = get_driver_list(o.pf, o.cmd(), 'E');
  CHECK(e.value[0].board == 1);
  CHECK(e.value[0].driver == 10);
  CHECK(get_driver_list(o.pf, o.cmd(), 'U').unknown());
  CHECK(get_driver_list(o.pf, o.cmd(), 'V').state == VState::Bad);
}

TEST_CASE("values: strings", "[values]") {
  CHECK(unquote("\"plain\"") == "plain");
  CHECK(unquote("\"say \"\"hi\"\"\"") == "say \"hi\"");
  CHECK(unquote("\"Bob's\"") == "Bobs");  // 'x lower-cases x and drops the apostrophe
  CHECK(unquote("\"'Tool 'A\"") == "tool a");
  CHECK(unquote("\"it''s\"") == "it's");         // '' is one apostrophe
  CHECK(unquote("\"'1 and '\"") == "'1 and '");  // ' before a non-letter is kept
  CHECK(unquote("raw") == "raw");

  One o = cmd("M563 P0 S\"Left \"\"hot\"\" end\" D0 H{1}");
  auto s = get_string(o.pf, o.cmd(), 'S');
  CHECK(s.known());
  CHECK(s.value == "Left \"hot\" end");
  CHECK(get_string(o.pf, o.cmd(), 'H').unknown());
  CHECK(get_string(o.pf, o.cmd(), 'Z').absent());
  CHECK(get_string(o.pf, o.cmd(), 'D').value == "0");  // unquoted text is taken raw

  One m = cmd("M98 Pmacros/park.g");
  CHECK(get_string(m.pf, m.cmd(), 'P').value == "macros/park.g");
  One q = cmd("M98 P\"park.g\" S1");
  CHECK(get_string(q.pf, q.cmd(), 'P').value == "park.g");
  One none = cmd("M98 P");
  CHECK(get_string(none.pf, none.cmd(), 'P').state == VState::Bad);
}
