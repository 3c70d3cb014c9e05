// The streaming JSON writer (json_writer.h).
#include "lint/render/json_writer.h"

#include <fmt/format.h>

#include <cstdint>

#include "lint/base/bytes8.h"

namespace rrflint {

void JsonWriter::newline(size_t depth) {
  if (indent_ < 0) return;
  out_ += '\n';
  out_.append(depth * static_cast<size_t>(indent_), ' ');
}

void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (empty_.empty()) return;  // the top-level value
  if (!empty_.back()) out_ += ',';
  empty_.back() = false;
  newline(empty_.size());
}

void JsonWriter::key(std::string_view k) {
  if (!empty_.back()) out_ += ',';
  empty_.back() = false;
  newline(empty_.size());
  string(k);
  out_ += indent_ < 0 ? ":" : ": ";
  after_key_ = true;
}

void JsonWriter::open(char c) {
  before_value();
  out_ += c;
  empty_.push_back(true);
}

void JsonWriter::close(char c) {
  const bool was_empty = empty_.back();
  empty_.pop_back();
  if (!was_empty) newline(empty_.size());
  out_ += c;
}

void JsonWriter::value(std::string_view s) {
  before_value();
  string(s);
}

void JsonWriter::value(int64_t n) {
  before_value();
  fmt::format_to(std::back_inserter(out_), "{}", n);
}

void JsonWriter::value(uint64_t n) {
  before_value();
  fmt::format_to(std::back_inserter(out_), "{}", n);
}

void JsonWriter::value(bool b) {
  before_value();
  out_ += b ? "true" : "false";
}

void JsonWriter::null() {
  before_value();
  out_ += "null";
}

namespace {

// Do the 8 bytes at p need no escape (no control byte, '"' or '\\')?
bool no_escape8(const char* p) {
  const uint64_t x = bytes8::load(p);
  return !bytes8::any_below(x, 0x20) && !bytes8::any_equal(x, '"') && !bytes8::any_equal(x, '\\');
}

}  // namespace

void JsonWriter::string(std::string_view s) {
  out_ += '"';
  size_t run = 0;  // start of the bytes not yet copied
  for (size_t i = 0; i < s.size(); ++i) {
    while (i + 8 <= s.size() && no_escape8(s.data() + i)) i += 8;
    if (i == s.size()) break;
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out_.append(s.substr(run, i - run));
    run = i + 1;
    switch (c) {
      case '"': out_ += "\\\""; break;
      case '\\': out_ += "\\\\"; break;
      case '\b': out_ += "\\b"; break;
      case '\f': out_ += "\\f"; break;
      case '\n': out_ += "\\n"; break;
      case '\r': out_ += "\\r"; break;
      case '\t': out_ += "\\t"; break;
      default: fmt::format_to(std::back_inserter(out_), "\\u{:04x}", c);
    }
  }
  out_.append(s.substr(run));
  out_ += '"';
}

}  // namespace rrflint
