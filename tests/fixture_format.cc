#include "tests/fixture_format.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace fs = std::filesystem;

namespace rrflint::fixture {

fs::path fixture_root() { return fs::path(RRFLINT_SOURCE_DIR) / "fixtures"; }

std::string rel(const fs::path& p) { return fs::relative(p, fs::path(RRFLINT_SOURCE_DIR)).generic_string(); }

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::pair<size_t, size_t>> split_lines(std::string_view t) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t b = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] != '\n' && t[i] != '\r') continue;
    out.emplace_back(b, i);
    if (t[i] == '\r' && i + 1 < t.size() && t[i + 1] == '\n') ++i;
    b = i + 1;
  }
  if (b < t.size() || out.empty()) out.emplace_back(b, t.size());
  return out;
}

size_t find_expect(std::string_view line) {
  for (size_t k = line.find(';'); k != std::string_view::npos; k = line.find(';', k + 1)) {
    size_t q = k + 1;
    while (q < line.size() && (line[q] == ' ' || line[q] == '\t')) ++q;
    if (line.substr(q).starts_with("expect:")) return k;
  }
  return std::string_view::npos;
}

bool parse_expect_list(std::string_view s, std::vector<ExpectItem>& out, std::string& err) {
  size_t i = 0;
  auto blanks = [&] {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  };
  auto digit = [&](size_t k) { return k < s.size() && s[k] >= '0' && s[k] <= '9'; };
  for (;;) {
    blanks();
    ExpectItem item;
    size_t b = i;
    // Rule names are kebab-case and may hold a version with dots (`m568-before-3.3`).
    while (i < s.size() &&
           ((s[i] >= 'a' && s[i] <= 'z') || digit(i) || s[i] == '-' || (s[i] == '.' && i > b && digit(i + 1))))
      ++i;
    if (i == b) {
      err = i < s.size() ? fmt::format("expected a rule name at '{}'", s.substr(i)) : "expected a rule name";
      return false;
    }
    item.rule = std::string(s.substr(b, i - b));
    if (i < s.size() && s[i] == '@') {
      ++i;
      size_t d = i;
      uint64_t col = 0;
      while (digit(i) && i - d < 9) col = col * 10 + static_cast<uint64_t>(s[i++] - '0');
      if (i == d || digit(i)) {
        err = fmt::format("expected a column number (1 or more) after '{}@'", item.rule);
        return false;
      }
      if (col == 0) {
        err = fmt::format("'{}@0': columns are 1-based", item.rule);
        return false;
      }
      item.column = static_cast<uint32_t>(col);
    }
    blanks();
    if (i < s.size() && s[i] == '"') {
      size_t close = s.find('"', i + 1);
      if (close == std::string_view::npos) {
        err = "unterminated message substring";
        return false;
      }
      item.substring = std::string(s.substr(i + 1, close - i - 1));
      i = close + 1;
      blanks();
    }
    out.push_back(std::move(item));
    if (i >= s.size()) return true;
    if (s[i] != ',') {
      err = fmt::format("expected ',' between expectations at '{}'", s.substr(i));
      return false;
    }
    ++i;
  }
}

ReadExpectations read_expectations(std::string_view text, const std::string& sd_path, const std::string& where) {
  ReadExpectations r;
  r.blanked = std::string(text);
  const auto lines = split_lines(text);
  std::vector<size_t> pending;  // own-line expectations waiting for their line (indices into r.expectations)
  for (size_t n = 0; n < lines.size(); ++n) {
    const auto [b, e] = lines[n];
    std::string_view line = text.substr(b, e - b);
    const size_t semi = find_expect(line);
    if (semi == std::string_view::npos) {
      for (size_t k : pending) r.expectations[k].line = static_cast<uint32_t>(n + 1);
      pending.clear();
      continue;
    }
    const bool own_line = line.substr(0, semi).find_first_not_of(" \t") == std::string_view::npos;
    std::string_view list = line.substr(line.find("expect:", semi) + 7);
    std::vector<ExpectItem> items;
    std::string err;
    if (!parse_expect_list(list, items, err))
      r.errors.push_back(fmt::format("{}:{}: malformed expectation: {}", where, n + 1, err));
    for (ExpectItem& item : items) {
      r.expectations.push_back(Expectation{sd_path, static_cast<uint32_t>(n + 1), std::move(item)});
      if (own_line) pending.push_back(r.expectations.size() - 1);
    }
    std::fill(r.blanked.begin() + static_cast<ptrdiff_t>(b + semi + 1), r.blanked.begin() + static_cast<ptrdiff_t>(e),
              ' ');
  }
  if (!pending.empty())
    r.errors.push_back(
        fmt::format("{}: an own-line expectation at the end of the file has no line to apply to", where));
  return r;
}

namespace {

bool is_fixed_file(const fs::path& p) { return p.filename().string().ends_with(".fixed.g"); }

}  // namespace

std::vector<FixtureCase> discover_cases(const fs::path& dir) {
  std::vector<FixtureCase> cases;
  const std::string rule = dir.filename().string();
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(dir)) entries.push_back(e.path());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& p : entries) {
    FixtureCase c;
    c.rule = rule;
    c.path = p;
    if (fs::is_directory(p)) {
      c.name = rule + "/" + p.filename().string();
      c.label = p.filename().string() + "/";
      std::vector<fs::path> files;
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) {
        const std::string sd = "/" + fs::relative(f, p).generic_string();
        if (is_fixed_file(f)) {
          c.fixed[sd.substr(0, sd.size() - 8) + ".g"] = f;  // "X.fixed.g" -> "X.g"
          continue;
        }
        c.files.push_back(CardFile{sd, f, read_bytes(f), {}});
      }
    } else if (p.extension() == ".g" && !is_fixed_file(p)) {
      c.name = rule + "/" + p.filename().string();
      c.label = p.filename().string();
      c.files.push_back(CardFile{"/sys/config.g", p, read_bytes(p), {}});
      fs::path fixed = p;
      fixed.replace_extension(".fixed.g");
      if (fs::exists(fixed)) c.fixed["/sys/config.g"] = fixed;
    } else {
      continue;  // .fixed.g files, snapshot.txt
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<fs::path> fixture_dirs() {
  std::vector<fs::path> dirs;
  if (!fs::is_directory(fixture_root())) return dirs;
  for (const auto& e : fs::directory_iterator(fixture_root()))
    if (e.is_directory()) dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

fs::path snapshot_path(const fs::path& dir) { return dir / "snapshot.txt"; }

std::vector<Expectation> read_case_expectations(FixtureCase& c, std::vector<std::string>& errors) {
  std::vector<Expectation> all;
  for (CardFile& f : c.files) {
    ReadExpectations r = read_expectations(f.original, f.sd_path, rel(f.disk));
    f.blanked = std::move(r.blanked);
    all.insert(all.end(), r.expectations.begin(), r.expectations.end());
    errors.insert(errors.end(), r.errors.begin(), r.errors.end());
  }
  return all;
}

void parse_options_words(std::string_view words_text, CaseOptions& o, const std::string& where,
                         std::vector<std::string>& errors) {
  std::istringstream words{std::string(words_text)};
  std::string w;
  while (words >> w) {
    std::string arg;
    if (w == "--tool-changer") {
      o.lint.tool_changer = true;
    } else if (w == "--unsafe-fixes") {
      o.unsafe_fixes = true;
    } else if (w == "--extend-select" && words >> arg) {
      o.lint.extend_select.push_back(arg);  // another rule on as well (RRF900 needs a rule to suppress)
    } else if (w == "--firmware" && words >> arg) {
      if (auto v = Version::parse(arg)) o.lint.firmware = *v;
      else errors.push_back(fmt::format("{}:1: bad --firmware '{}'", where, arg));
    } else if (w == "--board" && words >> arg) {
      if (auto b = parse_board(arg)) o.lint.board = *b;
      else errors.push_back(fmt::format("{}:1: bad --board '{}'", where, arg));
    } else {
      errors.push_back(fmt::format("{}:1: unknown rrflint-options word '{}'", where, w));
    }
  }
}

CaseOptions read_options(const FixtureCase& c, std::vector<std::string>& errors) {
  CaseOptions o;
  o.lint.select = {c.rule};
  const CardFile* config = nullptr;
  for (const CardFile& f : c.files)
    if (f.sd_path == "/sys/config.g") config = &f;
  if (!config) return o;
  std::string_view text = config->original;
  const auto lines = split_lines(text);
  read_options_line(text.substr(0, lines.front().second), o, rel(config->disk), errors);
  // Options are read from line 1 only: a comment line further down that starts like one would be ignored, and the
  // case would run with options other than it says.
  for (size_t i = 1; i < lines.size(); ++i) {
    std::string_view line = text.substr(lines[i].first, lines[i].second - lines[i].first);
    line.remove_prefix(std::min(line.size(), line.find_first_not_of(" \t")));
    if (!line.starts_with(';')) continue;
    line.remove_prefix(1);
    line.remove_prefix(std::min(line.size(), line.find_first_not_of(" \t")));
    if (line.starts_with("rrflint-options:"))
      errors.push_back(fmt::format("{}:{}: rrflint-options must be on line 1 (here they would be ignored)",
                                   rel(config->disk), i + 1));
  }
  return o;
}

bool read_options_line(std::string_view line, CaseOptions& o, const std::string& where,
                       std::vector<std::string>& errors) {
  const size_t at = line.find("rrflint-options:");
  if (at == std::string_view::npos || line.substr(0, at).find(';') == std::string_view::npos) return false;
  std::string_view rest = line.substr(at + 16);
  rest = rest.substr(0, rest.find(';'));  // an expectation may follow on the same line
  parse_options_words(rest, o, where, errors);
  return true;
}

}  // namespace rrflint::fixture
