#include "lint/boot/infer.h"

#include <algorithm>
#include <initializer_list>
#include <fmt/format.h>

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
  while (p < text.size() && (std::isalnum(static_cast<unsigned char>(text[p])) || text[p] == '.' || text[p] == '-')) ++p;
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
  std::vector<Evidence> ev;
  // Stated versions and boards in config.g's comments (config tool headers).
  std::optional<Evidence> stated;
  std::optional<std::pair<Board, Location>> stated_board;
  if (config) {
    const ParsedFile& pf = config->parsed;
    int seen = 0;
    for (const Line& line : pf.lines) {
      if (line.comment.empty()) continue;
      if (++seen > 40) break;
      std::string_view txt = pf.text(line.comment);
      Location loc{config->source->id(), line.comment};
      if (!stated) {
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
              stated = Evidence{Evidence::Kind::Stated, *v, fmt::format("config.g header states version {}", v->str()), loc};
            break;
          }
        }
      }
      if (!stated_board) {
        std::string l = to_lower(txt);
        auto found = [&](std::string_view s) { return l.find(s) != std::string::npos; };
        if (found("6hc") || found("6xd") || found("mb 6")) stated_board = {{Board::Duet3_6HC, loc}};
        else if (found("mini 5") || found("mini5")) stated_board = {{Board::Duet3_Mini, loc}};
        else if (found("maestro")) stated_board = {{Board::Maestro, loc}};
        else if (found("duet wifi") || found("duet 2") || found("duet ethernet") || found("duetwifi") || found("duet2"))
          stated_board = {{Board::Duet2, loc}};
      }
    }
  }
  if (stated) ev.push_back(*stated);
  // Syntax evidence from every file.
  bool any_m584_e = false;
  std::optional<Evidence> extruder_use, m305, m950, vars, arrays, meta;
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const FileUnit& u = m.unit(i);
    const ParsedFile& pf = u.parsed;
    const FileId f = u.source->id();
    for (uint32_t li = 0; li < pf.lines.size() && !(vars && meta && arrays); ++li) {
      if (pf.lines.kind(li) != LineKind::Meta) continue;  // read from the record: most lines are not
      const Line& line = pf.lines[li];
      if (!vars && (line.meta == MetaKind::Var || line.meta == MetaKind::Global || line.meta == MetaKind::Set))
        vars = Evidence{Evidence::Kind::Floor, Version(3, 3, 0), fmt::format("'{}' variables need RRF 3.3 or later", meta_keyword(line.meta)), {f, line.code}};
      if (!meta) meta = Evidence{Evidence::Kind::Floor, kRrf3_1, "meta commands need RRF 3.01 or later", {f, line.code}};
      if (!arrays && has_array_literal(pf.text(line.meta_arg)))
        arrays = Evidence{Evidence::Kind::Floor, kRrf3_5, "array expressions need RRF 3.5 or later", {f, line.meta_arg}};
    }
    // The first command of these codes (no fraction) for which `pred` holds, in file order; UINT32_MAX if none.
    auto first_of = [&](std::initializer_list<int> numbers, auto pred) {
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
    };
    auto any = [](const Command&) { return true; };
    if (!m305)
      if (const uint32_t ci = first_of({305}, any); ci != UINT32_MAX)
        m305 = Evidence{Evidence::Kind::Ceiling, Version(2, 5, 1), "M305 configures heaters the RRF 2 way", {f, pf.commands[ci].span}};
    if (!m950)
      if (const uint32_t ci = first_of({950, 308}, any); ci != UINT32_MAX)
        m950 = Evidence{Evidence::Kind::Floor, Version(3, 0, 0), fmt::format("M{} needs RRF 3.0 or later", pf.commands[ci].number),
                        {f, pf.commands[ci].span}};
    if (first_of({584}, [&](const Command& c) { return bool(pf.find(c, 'E')); }) != UINT32_MAX) any_m584_e = true;
    if (!extruder_use) {
      const uint32_t d = first_of({563}, [&](const Command& c) {
        auto dl = get_int_list(pf, c, 'D');
        return dl.known() && !dl.value.empty() && dl.value.front() >= 0;
      });
      const uint32_t e = first_of({92, 906, 350, 203, 201, 566}, [&](const Command& c) {
        ParamRef p = pf.find(c, 'E');
        return p && (p->kind == ValueKind::Number || p->kind == ValueKind::List);
      });
      if (d != UINT32_MAX && d < e)
        extruder_use = Evidence{Evidence::Kind::Ceiling, Version(3, 2, 2), "tools use extruders but no M584 E creates any (RRF 3.3+ has no default extruder)", {f, pf.commands[d].span}};
      else if (e != UINT32_MAX)
        extruder_use = Evidence{Evidence::Kind::Ceiling, Version(3, 2, 2), fmt::format("M{} sets E values but no M584 E creates an extruder (RRF 3.3+ has no default extruder)", pf.commands[e].number), {f, pf.commands[e].span}};
    }
  }
  for (auto* e : {&m305, &m950, &meta, &vars, &arrays})
    if (*e) ev.push_back(**e);
  if (extruder_use && !any_m584_e) ev.push_back(*extruder_use);
  t.evidence = ev;

  if (given) {
    t.version = *given;
    t.version_given = true;
    t.reason = fmt::format("target RRF {} (given)", given->str());
  } else {
    Version floor(1, 0, 0), ceiling = kLatestVersion;
    const Evidence *floor_ev = nullptr, *ceil_ev = nullptr;
    for (const Evidence& e : t.evidence) {
      if (e.kind == Evidence::Kind::Floor && e.version > floor) floor = e.version, floor_ev = &e;
      if (e.kind == Evidence::Kind::Ceiling && e.version < ceiling) ceiling = e.version, ceil_ev = &e;
    }
    if (floor > ceiling && ceil_ev) {  // (no ceil_ev: a floor above the newest known release, "version 4")
      t.version = series_latest(floor);
      t.reason = fmt::format("target RRF {}: {} although {}; the newer evidence wins", t.version.str(),
                             floor_ev->what, ceil_ev->what);
    } else if (stated && stated->kind == Evidence::Kind::Stated && series_latest(stated->version) >= floor && series_latest(stated->version) <= ceiling) {
      t.version = series_latest(stated->version);
      t.reason = fmt::format("target RRF {}: {}", t.version.str(), stated->what);
    } else if (ceil_ev) {
      t.version = ceiling;
      t.reason = fmt::format("target RRF {}: {}", t.version.str(), ceil_ev->what);
    } else {
      t.version = kLatestVersion;
      t.reason = floor_ev ? fmt::format("target RRF {} (newest known; {})", t.version.str(), floor_ev->what)
                          : fmt::format("target RRF {} (newest known; nothing in the files says otherwise)", t.version.str());
      if (stated && stated->kind == Evidence::Kind::Stated && series_latest(stated->version) < floor)
        t.reason += fmt::format("; the header's version {} is older than the syntax used", stated->version.str());
    }
  }
  if (given_board) {
    t.board = *given_board;
    t.board_given = true;
    t.board_reason = fmt::format("board {} (given)", board_name(t.board));
  } else if (stated_board) {
    t.board = stated_board->first;
    t.board_reason = fmt::format("board {} (named in config.g's header)", board_name(t.board));
  } else {
    t.board_reason = "board unknown: board limits use the largest board";
  }
  return t;
}

}  // namespace rrflint
