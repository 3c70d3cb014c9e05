#include "lint/boot/infer.h"

#include <fmt/format.h>
#include <algorithm>
#include <initializer_list>

#include "lint/syntax/values.h"

namespace rrflint {
namespace {

std::optional<Version> version_after(std::string_view text, std::string_view marker, bool* major_only = nullptr) {
  std::string lower = to_lower(text);
  size_t at = lower.find(marker);
  if (at == std::string::npos) return std::nullopt;
  size_t p = at + marker.size();
  while (p < text.size() && (text[p] == ' ' || text[p] == 'v' || text[p] == 'V' || text[p] == ':')) ++p;
  size_t b = p;
  while (p < text.size() && (std::isalnum(static_cast<unsigned char>(text[p])) || text[p] == '.' || text[p] == '-'))
    ++p;
  std::string_view cand = text.substr(b, p - b);
  while (!cand.empty() && (cand.back() == '.' || cand.back() == '-')) cand.remove_suffix(1);
  if (major_only) *major_only = cand.find('.') == std::string_view::npos;
  auto v = Version::parse(cand);
  if (!v) {  // "3.3RC2" style suffixes: keep the numeric part
    size_t q = 0;
    while (q < cand.size() && (std::isdigit(static_cast<unsigned char>(cand[q])) || cand[q] == '.')) ++q;
    v = Version::parse(cand.substr(0, q));
  }
  return v;
}

bool has_array_literal(std::string_view e) {
  int braces = 0, parens = 0;
  bool quote = false;
  for (char c : e) {
    if (quote) {
      if (c == '"') quote = false;
      continue;
    }
    if (c == '"') quote = true;
    else if (c == '{') ++braces;
    else if (c == '}') --braces;
    else if (c == '(' || c == '[') ++parens;
    else if (c == ')' || c == ']') --parens;
    else if (c == ',' && braces > 0 && parens == 0) return true;
  }
  return false;
}

// Calls `f(text, loc)` on each of config.g's first 40 comments (where config tools write their headers) until it
// returns true.
template <class F>
void scan_header(const FileUnit& config, F&& f) {
  const ParsedFile& pf = config.parsed;
  int seen = 0;
  for (const Line& line : pf.lines) {
    if (line.comment.empty()) continue;
    if (++seen > 40) break;
    if (f(pf.text(line.comment), Location{config.source->id(), line.comment})) return;
  }
}

// The firmware version stated in config.g's header comments.
std::optional<Evidence> stated_version(const FileUnit* config) {
  std::optional<Evidence> stated;
  if (!config) return stated;
  scan_header(*config, [&](std::string_view txt, Location loc) {
    for (std::string_view marker : {"firmware version", "configuration tool", "reprapfirmware version"}) {
      bool major_only = false;
      if (auto v = version_after(txt, marker, &major_only)) {
        // "firmware version 3" names the series only: a floor, not a version.
        if (major_only && v->major < 3)
          stated = Evidence{Evidence::Kind::Ceiling, Version(2, 5, 1),
                            fmt::format("config.g header states firmware version {}", v->major), loc};
        else if (major_only)
          stated = Evidence{Evidence::Kind::Floor, Version(v->major, 0, 0),
                            fmt::format("config.g header states firmware version {}", v->major), loc};
        else
          stated =
              Evidence{Evidence::Kind::Stated, *v, fmt::format("config.g header states version {}", v->str()), loc};
        return true;
      }
    }
    return false;
  });
  return stated;
}

// The board named in config.g's header comments.
std::optional<Board> stated_board(const FileUnit* config) {
  std::optional<Board> board;
  if (!config) return board;
  scan_header(*config, [&](std::string_view txt, Location) {
    std::string l = to_lower(txt);
    auto found = [&](std::string_view s) { return l.find(s) != std::string::npos; };
    if (found("6hc") || found("6xd") || found("mb 6")) board = Board::Duet3_6HC;
    else if (found("mini 5") || found("mini5")) board = Board::Duet3_Mini;
    else if (found("maestro")) board = Board::Maestro;
    else if (found("duet wifi") || found("duet 2") || found("duet ethernet") || found("duetwifi") || found("duet2"))
      board = Board::Duet2;
    return board.has_value();
  });
  return board;
}

// The first meta command (RRF 3.01), variable (3.3) and array expression (3.5) of the machine, in file order.
struct MetaEvidence {
  std::optional<Evidence> meta, vars, arrays;
};

MetaEvidence meta_evidence(const Machine& m) {
  MetaEvidence out;
  auto& [meta, vars, arrays] = out;
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const FileUnit& u = m.unit(i);
    const ParsedFile& pf = u.parsed;
    const FileId f = u.source->id();
    for (uint32_t li = 0; li < pf.lines.size() && !(vars && meta && arrays); ++li) {
      if (pf.lines.kind(li) != LineKind::Meta) continue;  // read from the record: most lines are not
      const Line& line = pf.lines[li];
      if (!vars && (line.meta == MetaKind::Var || line.meta == MetaKind::Global || line.meta == MetaKind::Set))
        vars = Evidence{Evidence::Kind::Floor,
                        Version(3, 3, 0),
                        fmt::format("'{}' variables need RRF 3.3 or later", meta_keyword(line.meta)),
                        {f, line.code}};
      if (!meta)
        meta = Evidence{Evidence::Kind::Floor, kRrf3_1, "meta commands need RRF 3.01 or later", {f, line.code}};
      if (!arrays && has_array_literal(pf.text(line.meta_arg)))
        arrays =
            Evidence{Evidence::Kind::Floor, kRrf3_5, "array expressions need RRF 3.5 or later", {f, line.meta_arg}};
    }
  }
  return out;
}

// The first command of these codes (no fraction) for which `pred` holds, in file order; UINT32_MAX if none.
template <class Pred>
uint32_t first_of(const ParsedFile& pf, std::initializer_list<int> numbers, Pred pred) {
  uint32_t best = UINT32_MAX;
  for (int n : numbers)
    for (const uint32_t ci : pf.with_code('M', n)) {
      if (ci >= best) break;
      const Command& c = pf.commands[ci];
      if (c.fraction < 0 && pred(c)) {
        best = ci;
        break;
      }
    }
  return best;
}

bool any_command(const Command&) { return true; }

// M305 (RRF 2's heater set-up): a ceiling.
std::optional<Evidence> m305_evidence(const Machine& m) {
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    if (const uint32_t ci = first_of(pf, {305}, any_command); ci != UINT32_MAX)
      return Evidence{Evidence::Kind::Ceiling,
                      Version(2, 5, 1),
                      "M305 configures heaters the RRF 2 way",
                      {m.unit(i).source->id(), pf.commands[ci].span}};
  }
  return std::nullopt;
}

// M950 or M308 (RRF 3's devices and sensors): a floor.
std::optional<Evidence> m950_evidence(const Machine& m) {
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    if (const uint32_t ci = first_of(pf, {950, 308}, any_command); ci != UINT32_MAX)
      return Evidence{Evidence::Kind::Floor,
                      Version(3, 0, 0),
                      fmt::format("M{} needs RRF 3.0 or later", pf.commands[ci].number),
                      {m.unit(i).source->id(), pf.commands[ci].span}};
  }
  return std::nullopt;
}

// Tools or E values that use extruders no M584 E creates (3.3 and later have no default extruder): a ceiling.
std::optional<Evidence> extruder_evidence(const Machine& m) {
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    if (first_of(pf, {584}, [&](const Command& c) { return bool(pf.find(c, 'E')); }) != UINT32_MAX) return std::nullopt;
  }
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    const FileId f = m.unit(i).source->id();
    const uint32_t d = first_of(pf, {563}, [&](const Command& c) {
      auto dl = get_int_list(pf, c, 'D');
      return dl.known() && !dl.value.empty() && dl.value.front() >= 0;
    });
    const uint32_t e = first_of(pf, {92, 906, 350, 203, 201, 566}, [&](const Command& c) {
      ParamRef p = pf.find(c, 'E');
      return p && (p->kind == ValueKind::Number || p->kind == ValueKind::List);
    });
    if (d != UINT32_MAX && d < e)
      return Evidence{Evidence::Kind::Ceiling,
                      Version(3, 2, 2),
                      "tools use extruders but no M584 E creates any (RRF 3.3+ has no default extruder)",
                      {f, pf.commands[d].span}};
    if (e != UINT32_MAX)
      return Evidence{Evidence::Kind::Ceiling,
                      Version(3, 2, 2),
                      fmt::format("M{} sets E values but no M584 E creates an extruder (RRF 3.3+ has no default "
                                  "extruder)",
                                  pf.commands[e].number),
                      {f, pf.commands[e].span}};
  }
  return std::nullopt;
}

// The version from the evidence (t.evidence) when none is given: the newer evidence wins a conflict, then a
// stated version that fits the syntax, then the lowest ceiling, else the newest known release.
void choose_version(Target& t, const std::optional<Evidence>& stated) {
  Version floor(1, 0, 0), ceiling = kLatestVersion;
  const Evidence *floor_ev = nullptr, *ceil_ev = nullptr;
  for (const Evidence& e : t.evidence) {
    if (e.kind == Evidence::Kind::Floor && e.version > floor) floor = e.version, floor_ev = &e;
    if (e.kind == Evidence::Kind::Ceiling && e.version < ceiling) ceiling = e.version, ceil_ev = &e;
  }
  const bool stated_fits = stated && stated->kind == Evidence::Kind::Stated &&
                           series_latest(stated->version) >= floor && series_latest(stated->version) <= ceiling;
  if (floor > ceiling && ceil_ev) {  // (no ceil_ev: a floor above the newest known release, "version 4")
    t.version = series_latest(floor);
    t.reason = fmt::format("target RRF {}: {} although {}; the newer evidence wins", t.version.str(), floor_ev->what,
                           ceil_ev->what);
  } else if (stated_fits) {
    t.version = series_latest(stated->version);
    t.reason = fmt::format("target RRF {}: {}", t.version.str(), stated->what);
  } else if (ceil_ev) {
    t.version = ceiling;
    t.reason = fmt::format("target RRF {}: {}", t.version.str(), ceil_ev->what);
  } else {
    t.version = kLatestVersion;
    t.reason = floor_ev
                   ? fmt::format("target RRF {} (newest known; {})", t.version.str(), floor_ev->what)
                   : fmt::format("target RRF {} (newest known; nothing in the files says otherwise)", t.version.str());
    if (stated && stated->kind == Evidence::Kind::Stated && series_latest(stated->version) < floor)
      t.reason += fmt::format("; the header's version {} is older than the syntax used", stated->version.str());
  }
}

}  // namespace

Version series_latest(Version v) {
  if (v.major < 3) return Version(2, 5, 1);
  if (v.major > 3) return kLatestVersion;  // no such release yet: the newest known
  switch (v.minor) {
    case 0: return Version(3, 0, 0);
    case 1: return Version(3, 1, 1);
    case 2: return Version(3, 2, 2);
    case 3: return Version(3, 3, 0);
    case 4: return Version(3, 4, 6);
    case 5: return Version(3, 5, 4);
    default: return v.minor >= 6 ? kLatestVersion : v;
  }
}

Target infer_target(const Machine& m, const FileUnit* config, std::optional<Version> given,
                    std::optional<Board> given_board) {
  Target t;
  // Stated versions in config.g's comments (config tool headers), then syntax evidence from every file.
  const std::optional<Evidence> stated = stated_version(config);
  if (stated) t.evidence.push_back(*stated);
  const std::optional<Evidence> m305 = m305_evidence(m), m950 = m950_evidence(m);
  const MetaEvidence meta = meta_evidence(m);
  for (const std::optional<Evidence>* e : {&m305, &m950, &meta.meta, &meta.vars, &meta.arrays})
    if (*e) t.evidence.push_back(**e);
  if (std::optional<Evidence> e = extruder_evidence(m)) t.evidence.push_back(std::move(*e));

  if (given) {
    t.version = *given;
    t.version_given = true;
    t.reason = fmt::format("target RRF {} (given)", given->str());
  } else {
    choose_version(t, stated);
  }
  if (given_board) {
    t.board = *given_board;
    t.board_given = true;
    t.board_reason = fmt::format("board {} (given)", board_name(t.board));
  } else if (const std::optional<Board> board = stated_board(config)) {
    t.board = *board;
    t.board_reason = fmt::format("board {} (named in config.g's header)", board_name(t.board));
  } else {
    t.board_reason = "board unknown: board limits use the largest board";
  }
  return t;
}

}  // namespace rrflint
