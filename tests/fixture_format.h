// The fixture format (docs/fixtures.md): how fixtures/<rule-name>/ is laid out, the `; rrflint-options:` first
// line, and the `; expect:` comments. Only reading and parsing here; linting a case is tests/fixture_lint.h, and
// comparing the findings with the expectations is tests/fixtures_test.cc.
//
//   fixtures/<rule-name>/<case>.g        a one-file SD card: the file is /sys/config.g
//   fixtures/<rule-name>/<case>/         a whole SD card (sys/config.g, macros/x.g, …)
//   <case>.fixed.g, X.fixed.g beside X.g  the expected text after applying the rule's fixes
//   fixtures/<rule-name>/snapshot.txt    the text rendering of the rule's findings on every case
//
// Expectations: `; expect: a, b@5 "message part"` at the end of a code line, or on a line of its own where it
// applies to the next line that is not itself an expect line. `@5`: the finding starts at column 5 (1-based, in
// code points, as the text renderer prints it); without it any column matches.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lint/engine/linter.h"
#include "rules/registry.h"

namespace rrflint::fixture {

/// fixtures/ in the source tree.
std::filesystem::path fixture_root();
/// A path relative to the source tree, for messages ("fixtures/g10-missing-z/stale-z.g").
std::string rel(const std::filesystem::path& p);
std::string read_bytes(const std::filesystem::path& p);

/// Lines as rrflint counts them (LF, CRLF and lone CR), as [begin, end) offsets without the terminator.
std::vector<std::pair<size_t, size_t>> split_lines(std::string_view text);

/// One item of an `expect:` list: `rule-name`, `rule-name@7`, `rule-name "part"`, `rule-name@7 "part"`.
struct ExpectItem {
  std::string rule;
  std::optional<uint32_t> column;  // 1-based code points; nullopt: any column
  std::string substring;           // empty: any message
  bool operator==(const ExpectItem&) const = default;
};

/// Finds `; expect:` (blanks allowed after ';') in a line. Returns the offset of the ';' or npos.
size_t find_expect(std::string_view line);

/// Parses the list after `expect:` (`a, b@5 "text", …`). Returns false with `err` set when it is malformed; the
/// items before the fault are in `out`.
bool parse_expect_list(std::string_view list, std::vector<ExpectItem>& out, std::string& err);

/// An expectation placed in a file: the line it applies to.
struct Expectation {
  std::string sd_path;
  uint32_t line = 0;  // 1-based
  ExpectItem item;
};

/// The expectations of one file's text, and the text with their comments blanked to spaces (the ';' stays, so
/// every offset, line and column is unchanged). `where` names the file in error messages.
struct ReadExpectations {
  std::vector<Expectation> expectations;
  std::string blanked;
  std::vector<std::string> errors;  // "<where>:<line>: malformed expectation: …"
};
ReadExpectations read_expectations(std::string_view text, const std::string& sd_path, const std::string& where);

/// One file of a case's card.
struct CardFile {
  std::string sd_path;
  std::filesystem::path disk;  // where the fixture file lives, for messages
  std::string original;        // with the expectation comments
  std::string blanked;         // expectation text replaced by spaces (read_case_expectations)
};

struct FixtureCase {
  std::string rule;            // the rule under test (directory name)
  std::string name;            // "<rule>/<case>.g" or "<rule>/<case>"
  std::string label;           // the snapshot header: "<case>.g" or "<case>/"
  std::filesystem::path path;  // the .g file or the folder
  std::vector<CardFile> files;
  std::map<std::string, std::filesystem::path> fixed;  // sd_path -> its .fixed.g file
};

/// Every case of one fixture directory, sorted by name (the files of a card are not yet blanked).
std::vector<FixtureCase> discover_cases(const std::filesystem::path& dir);
/// Every directory under fixtures/, sorted.
std::vector<std::filesystem::path> fixture_dirs();
/// fixtures/<rule-name>/snapshot.txt
std::filesystem::path snapshot_path(const std::filesystem::path& dir);

/// Reads the expectations of every file of a case and fills in CardFile::blanked. Problems go to `errors`.
std::vector<Expectation> read_case_expectations(FixtureCase& c, std::vector<std::string>& errors);

/// How a case is linted: `; rrflint-options: …` on line 1 of sys/config.g.
struct CaseOptions {
  LintOptions lint;  // select = {the rule}, plus the options
  bool unsafe_fixes = false;
};
/// Parses the words after `rrflint-options:` (--firmware V, --board B, --tool-changer, --unsafe-fixes,
/// --extend-select RULE) into `o`. Problems go to `errors` as "<where>:1: …".
void parse_options_words(std::string_view words, CaseOptions& o, const std::string& where,
                         std::vector<std::string>& errors);
/// Reads a `; rrflint-options: …` line (a `;` after the words ends them) into `o`. False when the line holds no
/// such comment.
bool read_options_line(std::string_view line, CaseOptions& o, const std::string& where,
                       std::vector<std::string>& errors);
/// The options of a case: only its rule, and what line 1 of its sys/config.g says.
CaseOptions read_options(const FixtureCase& c, std::vector<std::string>& errors);

}  // namespace rrflint::fixture
