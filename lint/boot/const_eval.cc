#include "lint/boot/const_eval.h"

#include <cctype>
#include <charconv>

namespace rrflint {
namespace {

// A recursive-descent reader over the expression text; any construct it does not know gives Unknown.
class Eval {
 public:
  Eval(std::string_view s, const ConstEnv& env) : s_(s), env_(env) {}

  ConstValue all() {
    ConstValue v = disjunction();
    skip();
    return p_ == s_.size() ? v : ConstValue{};
  }

 private:
  std::string_view s_;
  const ConstEnv& env_;
  size_t p_ = 0;
  int depth_ = 0;

  void skip() {
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t')) ++p_;
  }
  bool eat(std::string_view op) {
    skip();
    if (s_.substr(p_, op.size()) != op) return false;
    p_ += op.size();
    return true;
  }
  static ConstValue truth(const ConstValue& v) {
    if (v.kind == ConstValue::Kind::Bool) return v;
    return {};  // RRF wants booleans for && || !: anything else is not a constant here
  }

  ConstValue disjunction() {
    ConstValue v = conjunction();
    while (eat("||")) {
      const ConstValue r = conjunction();
      const ConstValue a = truth(v), b = truth(r);
      v = a.known() && b.known() ? ConstValue::boolean(a.b || b.b) : ConstValue{};
    }
    return v;
  }
  ConstValue conjunction() {
    ConstValue v = equality();
    while (eat("&&")) {
      const ConstValue r = equality();
      const ConstValue a = truth(v), b = truth(r);
      v = a.known() && b.known() ? ConstValue::boolean(a.b && b.b) : ConstValue{};
    }
    return v;
  }
  ConstValue equality() {
    ConstValue v = concat();
    for (;;) {
      bool eq;
      if (eat("==")) eq = true;
      else if (eat("!=")) eq = false;
      else return v;
      const ConstValue r = concat();
      if (!v.known() || !r.known() || v.kind != r.kind) {
        v = {};
        continue;
      }
      const bool same = v.kind == ConstValue::Kind::String   ? v.str == r.str
                        : v.kind == ConstValue::Kind::Number ? v.num == r.num
                                                             : v.b == r.b;
      v = ConstValue::boolean(same == eq);
    }
  }
  ConstValue concat() {
    ConstValue v = unary();
    while (eat("^")) {
      const ConstValue r = unary();
      if (v.kind != ConstValue::Kind::String || r.kind != ConstValue::Kind::String) v = {};
      else v.str += r.str;
    }
    return v;
  }
  ConstValue unary() {
    if (++depth_ > 64) return {};
    ConstValue v;
    if (eat("!")) {
      const ConstValue a = truth(unary());
      v = a.known() ? ConstValue::boolean(!a.b) : ConstValue{};
    } else {
      v = primary();
    }
    --depth_;
    return v;
  }
  ConstValue primary() {
    skip();
    if (p_ >= s_.size()) return {};
    const char c = s_[p_];
    if (c == '(') {
      ++p_;
      ConstValue v = disjunction();
      return eat(")") ? v : ConstValue{};
    }
    if (c == '"') return string_literal();
    if (std::isdigit(static_cast<unsigned char>(c))) return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name();
    return {};
  }
  ConstValue string_literal() {
    std::string out;
    for (++p_; p_ < s_.size(); ++p_) {
      if (s_[p_] != '"') {
        out += s_[p_];
        continue;
      }
      if (p_ + 1 < s_.size() && s_[p_ + 1] == '"') {  // "" stands for one quote
        out += '"';
        ++p_;
        continue;
      }
      ++p_;
      return ConstValue::string(std::move(out));
    }
    return {};  // unterminated
  }
  ConstValue number() {
    const size_t b = p_;
    while (p_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[p_])) || s_[p_] == '.')) ++p_;
    double d = 0;
    const auto r = std::from_chars(s_.data() + b, s_.data() + p_, d);
    return r.ec == std::errc() && r.ptr == s_.data() + p_ ? ConstValue::number(d) : ConstValue{};
  }
  ConstValue name() {
    const size_t b = p_;
    while (p_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[p_])) || s_[p_] == '_' || s_[p_] == '.')) ++p_;
    const std::string_view n = s_.substr(b, p_ - b);
    skip();
    if (p_ < s_.size() && (s_[p_] == '(' || s_[p_] == '[')) return {};  // a function or an array element
    if (n == "true" || n == "false") return ConstValue::boolean(n == "true");
    if (n == "directories.system") return ConstValue::string(env_.system_dir);
    auto look = [&](const std::map<std::string, ConstValue>* m, std::string_view key) {
      if (!m) return ConstValue{};
      const auto it = m->find(std::string(key));
      return it == m->end() ? ConstValue{} : it->second;
    };
    if (n.starts_with("global.")) return look(env_.globals, n.substr(7));
    if (n.starts_with("var.")) return look(env_.vars, n.substr(4));
    return {};
  }
};

}  // namespace

ConstValue const_eval(std::string_view expr, const ConstEnv& env) { return Eval(expr, env).all(); }

}  // namespace rrflint
