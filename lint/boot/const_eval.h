// Values known at boot: the constant expressions RRF evaluates the same way at every boot (issue 15 §3), so that
// `M98 P{directories.system^"/tool_params.g"}` names a file rrflint can follow. Everything else is unknown.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace rrflint {

struct ConstValue {
  enum class Kind : uint8_t { Unknown, String, Number, Bool } kind = Kind::Unknown;
  std::string str;
  double num = 0;
  bool b = false;
  bool known() const { return kind != Kind::Unknown; }
  static ConstValue string(std::string s) { return {Kind::String, std::move(s), 0, false}; }
  static ConstValue number(double n) { return {Kind::Number, {}, n, false}; }
  static ConstValue boolean(bool v) { return {Kind::Bool, {}, 0, v}; }
};

/// What an expression may read: `directories.system` ("0:/sys/", with its trailing slash, unless an M505 moved
/// it), and the `global.` / `var.` names set to constants earlier on the same boot path (absent: unknown).
struct ConstEnv {
  std::string system_dir = "0:/sys/";
  const std::map<std::string, ConstValue>* globals = nullptr;
  const std::map<std::string, ConstValue>* vars = nullptr;
};

/// Evaluates `expr` (the text inside `{…}`, or a meta command's condition): string and number literals, `^`,
/// `==`/`!=`, `&&`/`||`/`!`, parentheses, `true`/`false`, and the names of ConstEnv. Anything else (other
/// operators, object model fields, functions, arrays) makes the result unknown.
ConstValue const_eval(std::string_view expr, const ConstEnv& env);

}  // namespace rrflint
