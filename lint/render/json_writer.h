// A streaming JSON writer for the `json` and `json-lines` formats: the same bytes nlohmann::json's dump() printed
// (indent 2, or compact), written as the findings are walked, without a document tree. At 50,000 findings the tree
// cost more than the lint (gen-corpus-big 100 MB: 4.6 G of 14 G instructions, and its memory).
//
// Keys are written in the order the caller gives them; the renderers give them sorted, as nlohmann's std::map
// did, so the output is unchanged. Strings must be valid UTF-8 (pass them through sanitize()); control characters
// are escaped as JSON requires.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rrflint {

class JsonWriter {
 public:
  /// `indent` < 0: compact (json-lines); else that many spaces per level, one member per line.
  JsonWriter(std::string& out, int indent) : out_(out), indent_(indent) {}

  void begin_object() { open('{'); }
  void end_object() { close('}'); }
  void begin_array() { open('['); }
  void end_array() { close(']'); }
  /// The next member's key (in an object).
  void key(std::string_view k);
  void value(std::string_view s);
  void value(const char* s) { value(std::string_view(s)); }
  void value(int64_t n);
  void value(uint64_t n);
  void value(int n) { value(int64_t{n}); }
  void value(uint32_t n) { value(uint64_t{n}); }
  void value(bool b);
  void null();
  /// Goes on inside `depth` containers that another writer opened, the innermost an array: `first`, whether the
  /// next element is its first. (A piece of a long array written apart from the rest: write_diagnostics_json.)
  void resume(size_t depth, bool first) {
    empty_.assign(depth, false);
    if (depth > 0) empty_.back() = first;
  }
  /// key(k) then value(v).
  template <typename T>
  void member(std::string_view k, const T& v) {
    key(k);
    value(v);
  }

 private:
  void open(char c);
  void close(char c);
  void before_value();  // the separator and indentation before an array element (a key did it for a member)
  void newline(size_t depth);
  void string(std::string_view s);

  std::string& out_;
  int indent_;
  std::vector<bool> empty_;  // per open container: nothing written in it yet
  bool after_key_ = false;
};

}  // namespace rrflint
