#include "lint/syntax/values.h"

#include <fmt/format.h>
#include <cmath>

namespace rrflint {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Parses a float at the start of `s` like RRF's SafeStrtof. Returns false if no digits.
bool parse_float(std::string_view s, double& out, size_t* used = nullptr) {
  size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  bool neg = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
  double v = 0;
  bool digits = false;
  while (i < s.size() && is_digit(s[i])) v = v * 10 + (s[i++] - '0'), digits = true;
  if (i < s.size() && s[i] == '.') {
    ++i;
    double scale = 0.1;
    while (i < s.size() && is_digit(s[i])) v += (s[i++] - '0') * scale, scale /= 10, digits = true;
  }
  if (!digits) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    size_t j = i + 1;
    bool eneg = false;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) eneg = s[j++] == '-';
    if (j < s.size() && is_digit(s[j])) {
      int e = 0;
      while (j < s.size() && is_digit(s[j])) {
        if (e < 100000) e = e * 10 + (s[j] - '0');
        ++j;
      }
      v = v * std::pow(10.0, eneg ? -e : e);
      i = j;
    }
  }
  out = neg ? -v : v;
  if (used) *used = i;
  return true;
}

bool parse_int(std::string_view s, int64_t& out) {
  size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  bool neg = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
  int64_t v = 0;
  size_t b = i;
  while (i < s.size() && is_digit(s[i])) {
    if (v < (int64_t(1) << 40)) v = v * 10 + (s[i] - '0');
    ++i;
  }
  if (i == b) return false;
  out = neg ? -v : v;
  return true;
}

bool parse_driver(std::string_view s, DriverId& out) {
  size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  uint32_t a = 0;
  size_t b = i;
  while (i < s.size() && is_digit(s[i])) a = a * 10 + uint32_t(s[i++] - '0'), a = a > 65535 ? 65535 : a;
  if (i == b) return false;
  if (i < s.size() && s[i] == '.') {
    ++i;
    uint32_t d = 0;
    size_t c = i;
    while (i < s.size() && is_digit(s[i])) d = d * 10 + uint32_t(s[i++] - '0'), d = d > 65535 ? 65535 : d;
    if (i == c) return false;
    out = DriverId{static_cast<uint16_t>(a), static_cast<uint16_t>(d), true};
  } else {
    out = DriverId{0, static_cast<uint16_t>(a), false};
  }
  return true;
}

// Calls f(item) for each item of a list value, as RRF reads them: a value, then on only if the very next
// character is ':'. Blanks after a ':' are skipped by number parsing; a blank before a ':' ends the list
// (docs/firmware-behaviour.md#numbers-and-lists). f returns false to stop.
template <class F>
void each_list_item(const ParsedFile& pf, const Param& p, F f) {
  std::string_view t = pf.source->text();
  const uint32_t e = p.value.end;
  uint32_t k = p.value.begin;
  for (;;) {
    while (k < e && (t[k] == ' ' || t[k] == '\t')) ++k;
    const uint32_t ib = k;
    int braces = 0;
    bool quote = false;
    while (k < e) {
      char ch = t[k];
      if (quote) {
        if (ch == '"') quote = false;
      } else if (ch == '"') {
        quote = true;
      } else if (ch == '{') {
        ++braces;
      } else if (ch == '}') {
        --braces;
      } else if (braces <= 0 && (ch == ':' || ch == ' ' || ch == '\t')) {
        break;
      }
      ++k;
    }
    if (!f(Span{ib, k})) return;
    if (k < e && t[k] == ':') {
      ++k;
      continue;
    }
    return;
  }
}

template <class T, class F>
Val<std::vector<T>> get_list(const ParsedFile& pf, const Command& c, char letter, F parse_one) {
  Val<std::vector<T>> v;
  ParamRef p = pf.find(c, letter);
  if (!p) return v;
  v.param = p;
  if (is_unknown_value(*p)) {
    v.state = VState::Unknown;
    return v;
  }
  if (p->kind != ValueKind::Number && p->kind != ValueKind::List) {
    v.state = VState::Bad;
    return v;
  }
  v.state = VState::Known;
  each_list_item(pf, *p, [&](Span s) {
    T item{};
    if (!parse_one(pf.text(s), item)) {
      v.state = VState::Bad;
      return false;
    }
    v.value.push_back(item);
    return true;
  });
  return v;
}

}  // namespace

std::string DriverId::str() const {
  return explicit_board ? fmt::format("{}.{}", board, driver) : fmt::format("{}", driver);
}

std::vector<Span> list_items(const ParsedFile& pf, const Param& p) {
  std::vector<Span> items;
  each_list_item(pf, p, [&](Span s) {
    items.push_back(s);
    return true;
  });
  return items;
}

Val<double> get_float(const ParsedFile& pf, const Command& c, char letter) {
  Val<double> v;
  ParamRef p = pf.find(c, letter);
  if (!p) return v;
  v.param = p;
  if (is_unknown_value(*p)) return v.state = VState::Unknown, v;
  double d = 0;
  if (p->kind != ValueKind::Number || !parse_float(pf.text(p->value), d)) return v.state = VState::Bad, v;
  v.state = VState::Known;
  v.value = d;
  return v;
}

Val<int64_t> get_int(const ParsedFile& pf, const Command& c, char letter) {
  Val<int64_t> v;
  ParamRef p = pf.find(c, letter);
  if (!p) return v;
  v.param = p;
  if (is_unknown_value(*p)) return v.state = VState::Unknown, v;
  int64_t i = 0;
  if ((p->kind != ValueKind::Number && p->kind != ValueKind::List) || !parse_int(pf.text(p->value), i))
    return v.state = VState::Bad, v;
  v.state = VState::Known;
  v.value = i;
  return v;
}

std::string unquote(std::string_view q) {
  std::string out;
  if (q.size() < 2 || q.front() != '"') return std::string(q);
  std::string_view body = q.substr(1, q.size() - 2);
  if (body.find_first_of("\"'") == std::string_view::npos) return std::string(body);  // nothing to undo
  out.reserve(body.size());
  for (size_t i = 0; i < body.size(); ++i) {
    char ch = body[i];
    if (ch == '"' && i + 1 < body.size() && body[i + 1] == '"') {
      out += '"';
      ++i;
    } else if (ch == '\'' && i + 1 < body.size()) {
      char n = body[i + 1];
      if (n == '\'') {
        out += '\'';
        ++i;
      } else if ((n >= 'A' && n <= 'Z') || (n >= 'a' && n <= 'z')) {
        out += static_cast<char>(n | 0x20);
        ++i;
      } else {
        out += ch;
      }
    } else {
      out += ch;
    }
  }
  return out;
}

Val<std::string> get_string(const ParsedFile& pf, const Command& c, char letter) {
  Val<std::string> v;
  ParamRef p = pf.find(c, letter);
  if (!p) return v;
  v.param = p;
  if (is_unknown_string(*p)) return v.state = VState::Unknown, v;
  if (p->kind == ValueKind::String) {
    std::string_view raw = pf.text(p->value);
    if (raw.size() < 2 || raw.back() != '"') return v.state = VState::Bad, v;
    v.value = unquote(raw);
  } else if (p->kind == ValueKind::None) {
    return v.state = VState::Bad, v;
  } else {
    v.value = std::string(pf.text(p->value));
  }
  v.state = VState::Known;
  return v;
}

Val<std::vector<double>> get_float_list(const ParsedFile& pf, const Command& c, char letter) {
  return get_list<double>(pf, c, letter, [](std::string_view s, double& d) { return parse_float(s, d); });
}
Val<std::vector<int64_t>> get_int_list(const ParsedFile& pf, const Command& c, char letter) {
  return get_list<int64_t>(pf, c, letter, [](std::string_view s, int64_t& d) { return parse_int(s, d); });
}
Val<std::vector<DriverId>> get_driver_list(const ParsedFile& pf, const Command& c, char letter) {
  return get_list<DriverId>(pf, c, letter, [](std::string_view s, DriverId& d) { return parse_driver(s, d); });
}

}  // namespace rrflint
