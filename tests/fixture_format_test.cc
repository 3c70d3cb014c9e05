// The fixture runner's own format reader (tests/fixture_format.h): `; expect:` lists with and without columns
// and messages, their placement, the blanking, malformed lists, and the rrflint-options words.
#include <catch2/catch.hpp>

#include "tests/fixture_format.h"

using namespace rrflint;
using namespace rrflint::fixture;

namespace {

std::vector<ExpectItem> parse_ok(std::string_view s) {
  std::vector<ExpectItem> out;
  std::string err;
  INFO("list: " << s);
  CHECK(parse_expect_list(s, out, err));
  CHECK(err.empty());
  return out;
}

std::string parse_error(std::string_view s) {
  std::vector<ExpectItem> out;
  std::string err;
  INFO("list: " << s);
  CHECK_FALSE(parse_expect_list(s, out, err));
  return err;
}

}  // namespace

TEST_CASE("expect lists: rule names, columns and message parts", "[fixture-format]") {
  using V = std::vector<ExpectItem>;
  CHECK(parse_ok(" g10-missing-z") == V{{"g10-missing-z", std::nullopt, ""}});
  CHECK(parse_ok(" g10-missing-z \"(-1.25)\"") == V{{"g10-missing-z", std::nullopt, "(-1.25)"}});
  CHECK(parse_ok(" g10-missing-z@5") == V{{"g10-missing-z", 5u, ""}});
  CHECK(parse_ok(" g10-missing-z@5 \"(-1.25)\"  ") == V{{"g10-missing-z", 5u, "(-1.25)"}});
  CHECK(parse_ok("\tg10-missing-z@12\"x\"") == V{{"g10-missing-z", 12u, "x"}});
  // Dots belong to a version in the name; a message may hold commas, '@' and ';'.
  CHECK(parse_ok(" m568-before-3.3@1") == V{{"m568-before-3.3", 1u, ""}});
  CHECK(parse_ok(" a@3 \"x, y@2; z\", b, c@40 \"\"") ==
        V{{"a", 3u, "x, y@2; z"}, {"b", std::nullopt, ""}, {"c", 40u, ""}});
}

TEST_CASE("malformed expect lists say what is wrong", "[fixture-format]") {
  CHECK(parse_error("") == "expected a rule name");
  CHECK(parse_error(" a,") == "expected a rule name");
  CHECK(parse_error(" G10-missing-z") == "expected a rule name at 'G10-missing-z'");
  CHECK(parse_error(" g10-missing-z@") == "expected a column number (1 or more) after 'g10-missing-z@'");
  CHECK(parse_error(" g10-missing-z@x") == "expected a column number (1 or more) after 'g10-missing-z@'");
  CHECK(parse_error(" g10-missing-z@1234567890") == "expected a column number (1 or more) after 'g10-missing-z@'");
  CHECK(parse_error(" g10-missing-z@0") == "'g10-missing-z@0': columns are 1-based");
  CHECK(parse_error(" g10-missing-z \"(-1.25)") == "unterminated message substring");
  CHECK(parse_error(" a b") == "expected ',' between expectations at 'b'");
  CHECK(parse_error(" a \"x\" @5") == "expected ',' between expectations at '@5'");
  CHECK(parse_error(" a@5x") == "expected ',' between expectations at 'x'");
}

TEST_CASE("expectations in a file: placement and blanking", "[fixture-format]") {
  const std::string text =
      "M584 X0 Y1 Z2\n"
      "G10 P0 X1 ; left ; expect: g10-missing-z@1 \"(-1.25)\"\n"
      "; expect: a, b@7\n"
      ";   expect: c\n"
      "\n"
      "G10 P1 X2\r\n"
      "G10 P2 X3 ; expect: d@";
  const ReadExpectations r = read_expectations(text, "/sys/config.g", "fixtures/x/y.g");
  REQUIRE(r.expectations.size() == 4);
  CHECK(r.expectations[0].line == 2);
  CHECK(r.expectations[0].item == ExpectItem{"g10-missing-z", 1u, "(-1.25)"});
  // Own-line expectations apply to the next line that is not an expect line (here a blank one).
  CHECK(r.expectations[1].line == 5);
  CHECK(r.expectations[1].item.rule == "a");
  CHECK(r.expectations[2].line == 5);
  CHECK(r.expectations[2].item == ExpectItem{"b", 7u, ""});
  CHECK(r.expectations[3].line == 5);
  CHECK(r.expectations[3].sd_path == "/sys/config.g");
  REQUIRE(r.errors.size() == 1);
  CHECK(r.errors[0] == "fixtures/x/y.g:7: malformed expectation: expected a column number (1 or more) after 'd@'");
  // Blanked to spaces after the ';', so offsets, lines and columns do not move.
  REQUIRE(r.blanked.size() == text.size());
  CHECK(r.blanked.substr(0, 25) == "M584 X0 Y1 Z2\nG10 P0 X1 ;");
  CHECK(r.blanked.find("expect") == std::string::npos);
  CHECK(r.blanked.find("G10 P1 X2\r\n") != std::string::npos);
  CHECK(r.blanked.find("\n;" + std::string(15, ' ') + "\n") != std::string::npos);  // "; expect: a, b@7"

  const ReadExpectations dangling = read_expectations("G1 X0\n; expect: a\n", "/sys/config.g", "f.g");
  REQUIRE(dangling.errors.size() == 1);
  CHECK(dangling.errors[0] == "f.g: an own-line expectation at the end of the file has no line to apply to");
}

TEST_CASE("rrflint-options words", "[fixture-format]") {
  CaseOptions o;
  std::vector<std::string> errors;
  parse_options_words(" --firmware 3.4.6 --board duet2 --tool-changer --unsafe-fixes --extend-select RRF331 ", o, "f.g",
                      errors);
  CHECK(errors.empty());
  CHECK(o.lint.firmware == Version::parse("3.4.6"));
  CHECK(o.lint.board == parse_board("duet2"));
  CHECK(o.lint.tool_changer);
  CHECK(o.unsafe_fixes);
  CHECK(o.lint.extend_select == std::vector<std::string>{"RRF331"});
  parse_options_words("--firmware banana --fix", o, "f.g", errors);
  CHECK(errors ==
        std::vector<std::string>{"f.g:1: bad --firmware 'banana'", "f.g:1: unknown rrflint-options word '--fix'"});
}
