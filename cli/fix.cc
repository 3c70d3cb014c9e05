// Applying fixes: conflict-free selection (whole fixes only), line-ending preservation, atomic writes that
// never lose data, the report file that never replaces an input, and unified diffs for --diff.
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <tuple>

#include "cli/cli.h"
#include "frontend/platform.h"

namespace rrflint::cli {
namespace {

// Inserted text written with "\n" gets the file's own line ending (a rule need not know it).
std::string with_eol(const std::string& s, std::string_view eol) {
  if (eol == "\n" || s.find('\r') != std::string::npos || s.find('\n') == std::string::npos) return s;
  std::string out;
  for (char c : s) {
    if (c == '\n') out += eol;
    else out += c;
  }
  return out;
}

}  // namespace

size_t apply_fixes(const SourceManager& sm, const std::vector<Diagnostic>& diags, const FixOptions& fo,
                   const std::function<bool(FileId)>& allowed, std::map<FileId, std::string>& texts,
                   std::map<FileId, size_t>* per_file, std::vector<const Diagnostic*>* applied_out) {
  std::map<FileId, std::vector<Span>> taken;
  std::map<FileId, std::vector<Edit>> accepted;
  size_t applied = 0;
  for (const Diagnostic& d : diags) {
    if (!d.fix || d.fix->edits.empty()) continue;
    if (d.fix->applicability == Applicability::Unsafe && !fo.unsafe) continue;
    bool ok = true;
    for (const Edit& e : d.fix->edits) {
      if (e.loc.file == kNoFile || !allowed(e.loc.file) || e.loc.span.end < e.loc.span.begin ||
          e.loc.span.end > sm.get(e.loc.file).size()) {
        ok = false;
        break;
      }
      // Overlap with an accepted edit (touching insertions at the same point also conflict: order unknown).
      for (const Span& s : taken[e.loc.file]) {
        const bool overlap = e.loc.span.begin < s.end && s.begin < e.loc.span.end;
        const bool same_point = (e.loc.span.empty() && (e.loc.span.begin == s.end || e.loc.span.begin == s.begin)) ||
                                (s.empty() && (s.begin == e.loc.span.end || s.begin == e.loc.span.begin));
        if (overlap || same_point) ok = false;
      }
      if (!ok) break;
    }
    if (!ok) continue;  // left for the next round
    for (const Edit& e : d.fix->edits) {
      taken[e.loc.file].push_back(e.loc.span);
      Edit copy = e;
      // An edit of line endings themselves (CR to LF) keeps the ones it writes.
      const std::string_view replaced = sm.get(e.loc.file).slice(e.loc.span);
      if (replaced.empty() || replaced.find_first_not_of("\r\n") != std::string_view::npos)
        copy.replacement = with_eol(e.replacement, sm.get(e.loc.file).usual_ending());
      accepted[e.loc.file].push_back(std::move(copy));
    }
    if (per_file) ++(*per_file)[d.fix->edits.front().loc.file];
    if (applied_out) applied_out->push_back(&d);
    ++applied;
  }
  for (auto& [file, edits] : accepted) {
    std::string& text = texts.try_emplace(file, sm.get(file).text()).first->second;
    std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
      return std::tie(a.loc.span.begin, a.loc.span.end) < std::tie(b.loc.span.begin, b.loc.span.end);
    });
    // Back to front, so earlier offsets stay valid.
    for (auto it = edits.rbegin(); it != edits.rend(); ++it)
      text.replace(it->loc.span.begin, it->loc.span.size(), it->replacement);
  }
  return applied;
}

namespace {

// Parse errors and ';'-cut expressions, by lower-cased SD path.
std::map<std::string, size_t> parse_problems(const MachineResult& r) {
  std::map<std::string, size_t> n;
  for (uint32_t i = 0; i < r.machine->unit_count(); ++i) {
    const FileUnit& u = r.machine->unit(i);
    n[to_lower(u.sd_path)] += u.parsed.errors.size() + u.parsed.semicolon_cuts.size();
  }
  return n;
}

size_t count_of(const std::map<std::string, size_t>& m, const std::string& key) {
  auto it = m.find(key);
  return it == m.end() ? 0 : it->second;
}

}  // namespace

bool parses_worse(const SourceFile& before, std::string after) {
  auto problems = [](const SourceFile& f) {
    const ParsedFile p = parse(f, ParseOptions{});
    return p.errors.size() + p.semicolon_cuts.size();
  };
  const SourceFile fixed(0, before.display_path(), before.sd_path(), TextBuffer(std::move(after)));
  return problems(fixed) > problems(before);
}

FixRounds run_fix_rounds(const SourceManager& sm, MachineResult& r, const FixOptions& fo,
                         const std::function<bool(FileId)>& allowed,
                         const std::function<void(const std::string& sd_path, const std::string& text)>& set_text,
                         const std::function<MachineResult()>& relint) {
  FixRounds out;
  std::set<std::string> frozen;  // lower-cased SD paths of files a round made worse
  auto may_fix = [&](FileId id) { return allowed(id) && !frozen.count(to_lower(sm.get(id).sd_path())); };
  for (int round = 0; round < fo.max_rounds; ++round) {
    std::map<FileId, std::string> texts;
    std::map<FileId, size_t> per_file;
    std::vector<const Diagnostic*> applied;
    const size_t n = apply_fixes(sm, r.diagnostics, fo, may_fix, texts, &per_file, &applied);
    if (n == 0) return out;
    std::map<std::string, std::string> before;  // this round's starting texts, by SD path
    for (const auto& [id, text] : texts) {
      const SourceFile& f = sm.get(id);
      before.try_emplace(f.sd_path(), f.text());
      out.original.try_emplace(f.sd_path(), f.text());
      out.display[f.sd_path()] = f.display_path();
      set_text(f.sd_path(), text);
    }
    MachineResult next = relint();
    const std::map<std::string, size_t> was = parse_problems(r), is = parse_problems(next);
    std::vector<std::string> worse;
    for (const auto& [sd, text] : before)
      if (count_of(is, to_lower(sd)) > count_of(was, to_lower(sd))) worse.push_back(sd);
    if (!worse.empty()) {
      // Undo the whole round (a fix may span files); `r` still describes the texts as they were before it.
      for (const auto& [sd, text] : before) set_text(sd, text);
      for (const std::string& sd : worse) {
        frozen.insert(to_lower(sd));
        std::vector<std::string>& codes = out.reverted[sd];
        for (const Diagnostic* d : applied) {
          const FileId f = d->fix->edits.front().loc.file;
          if (to_lower(sm.get(f).sd_path()) == to_lower(sd) &&
              std::find(codes.begin(), codes.end(), d->code) == codes.end())
            codes.emplace_back(d->code);
        }
        std::sort(codes.begin(), codes.end());
      }
      continue;
    }
    out.fixed += n;
    for (const auto& [id, k] : per_file) out.fixed_in[sm.get(id).sd_path()] += k;
    for (auto& [id, text] : texts) out.current[sm.get(id).sd_path()] = std::move(text);
    r = std::move(next);
  }
  std::map<FileId, std::string> scratch;
  out.settled = apply_fixes(sm, r.diagnostics, fo, may_fix, scratch) == 0;
  return out;
}

std::string outside_roots(const fs::path& path, const std::vector<fs::path>& roots, fs::path* real) {
  std::error_code ec;
  const bool link = fs::is_symlink(path, ec);
  const fs::path target = fs::canonical(path, ec);
  if (ec) return link ? "a symbolic link that leads nowhere" : "";  // a missing file: the caller's stat says so
  if (real) *real = target;
  if (target == fs::path(absolute_normal(path))) return "";  // no link on the way
  for (const fs::path& root : roots) {
    std::error_code rec;
    const fs::path real_root = fs::canonical(root, rec);
    if (!rec && path_below(target.string(), real_root.string())) return "";
  }
  return link ? fmt::format("a symbolic link to {}, outside the linted folders", target.string())
              : fmt::format("reached through a linked folder, it is {}, outside the linted folders", target.string());
}

bool write_atomic(const fs::path& path, const std::string& expected, const std::string& bytes,
                  const std::vector<fs::path>& roots, std::string* err) {
  auto fail = [&](std::string why) {
    if (err) *err = std::move(why);
    return false;
  };
  // A file reached through a symbolic link is written through it (the link stays), but only below the linted folders.
  fs::path target = path;
  if (std::string why = outside_roots(path, roots, &target); !why.empty()) return fail(why + ": not written");
  struct stat st {};
  if (::stat(target.string().c_str(), &st) != 0) return fail(fmt::format("cannot write: {}", std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) return fail("not a regular file: not written");
  // A file the user made read-only stays as it is, root or not: a rename would replace it regardless of its mode.
  if ((st.st_mode & 0222) == 0) return fail("read-only: not written (make it writable to let --fix change it)");
  // Without root, a file this user could not write in place is not replaced through the folder either.
  if (::geteuid() != 0 && ::access(target.string().c_str(), W_OK) != 0)
    return fail(fmt::format("not writable ({}): not written", std::strerror(errno)));
  std::string now_err;
  auto now = read_file(target.string(), &now_err);
  if (!now) return fail(now_err + ": not written");
  if (*now != expected) return fail("changed on disk while rrflint was running: not written");

  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::string tmpl = (dir / ("." + target.filename().string() + ".rrflint-XXXXXX")).string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0)
    return fail(
        fmt::format("cannot create a temporary file in {} ({}): not written", dir.string(), std::strerror(errno)));
  int write_errno = 0;
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      write_errno = n < 0 ? errno : EIO;
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (!write_errno && ::fsync(fd) != 0) write_errno = errno;
  // The same mode, owner and group as the file it replaces; a file whose owner cannot be kept is not replaced.
  bool kept = ::fchmod(fd, st.st_mode & 07777) == 0;
  if (::fchown(fd, st.st_uid, st.st_gid) != 0) kept = false;
  if (::close(fd) != 0 && !write_errno) write_errno = errno;
  auto give_up = [&](std::string why) {
    ::unlink(tmpl.c_str());
    return fail(std::move(why));
  };
  if (write_errno) return give_up(fmt::format("cannot write ({}): not written", std::strerror(write_errno)));
  if (!kept) return give_up("cannot keep its owner, group or mode: not written");
  // Changed since it was read (the content check above leaves a window while the new text is written)?
  struct stat again {};
  if (::stat(target.string().c_str(), &again) != 0 || again.st_ino != st.st_ino || again.st_size != st.st_size ||
      file_mtime_ns(again) != file_mtime_ns(st))
    return give_up("changed on disk while rrflint was running: not written");
  if (replace_file(tmpl.c_str(), target.string().c_str()) != 0)
    return give_up(fmt::format("cannot replace it ({}): not written", std::strerror(errno)));
  return true;
}

namespace {

// Lines to their line feeds (a CR is part of its line), so a diff reproduces the bytes exactly.
std::vector<std::string_view> split_keep(std::string_view s) {
  std::vector<std::string_view> out;
  size_t b = 0;
  while (b < s.size()) {
    size_t e = b;
    while (e < s.size() && s[e] != '\n') ++e;
    if (e < s.size()) ++e;
    out.push_back(s.substr(b, e - b));
    b = e;
  }
  return out;
}

struct Op {
  char kind;    // ' ', '-', '+'
  size_t a, b;  // line indices in before/after
};

// The edit script between two line lists: common prefix and suffix, then an LCS table on the middle (bounded;
// a huge middle is shown as one replaced block).
std::vector<Op> diff_ops(const std::vector<std::string_view>& a, const std::vector<std::string_view>& b) {
  size_t pre = 0;
  while (pre < a.size() && pre < b.size() && a[pre] == b[pre]) ++pre;
  size_t suf = 0;
  while (suf < a.size() - pre && suf < b.size() - pre && a[a.size() - 1 - suf] == b[b.size() - 1 - suf]) ++suf;
  const size_t n = a.size() - pre - suf, m = b.size() - pre - suf;
  std::vector<Op> ops;
  for (size_t i = 0; i < pre; ++i) ops.push_back({' ', i, i});
  if (n * m <= 4'000'000) {
    std::vector<std::vector<uint32_t>> L(n + 1, std::vector<uint32_t>(m + 1, 0));
    for (size_t i = n; i-- > 0;)
      for (size_t j = m; j-- > 0;)
        L[i][j] = a[pre + i] == b[pre + j] ? L[i + 1][j + 1] + 1 : std::max(L[i + 1][j], L[i][j + 1]);
    size_t i = 0, j = 0;
    while (i < n || j < m) {
      if (i < n && j < m && a[pre + i] == b[pre + j]) {
        ops.push_back({' ', pre + i, pre + j});
        ++i, ++j;
      } else if (i < n && (j == m || L[i + 1][j] >= L[i][j + 1])) {
        ops.push_back({'-', pre + i, pre + j});  // removals first, as diff(1) prints them
        ++i;
      } else {
        ops.push_back({'+', pre + i, pre + j});
        ++j;
      }
    }
  } else {
    for (size_t i = 0; i < n; ++i) ops.push_back({'-', pre + i, pre});
    for (size_t j = 0; j < m; ++j) ops.push_back({'+', pre + n, pre + j});
  }
  for (size_t k = 0; k < suf; ++k) ops.push_back({' ', a.size() - suf + k, b.size() - suf + k});
  return ops;
}

// A line as it is, to its line feed: `git apply` and `patch` split a file at line feeds only, so a lone CR (a file
// saved with CR line endings) stays inside its line, as diff(1) shows it.
void emit_line(std::string& out, char kind, std::string_view line) {
  out += kind;
  out += line;
  if (!line.ends_with('\n')) out += "\n\\ No newline at end of file\n";
}

}  // namespace

std::string unified_diff(std::string_view before, std::string_view after, const std::string& path) {
  if (before == after) return "";
  const auto a = split_keep(before), b = split_keep(after);
  const std::vector<Op> ops = diff_ops(a, b);
  constexpr size_t kContext = 3;
  // A name with a space ends with a tab, as git writes it, so that patch(1) reads the whole name.
  const char* tab = path.find(' ') != std::string::npos ? "\t" : "";
  std::string out = fmt::format("--- a/{}{}\n+++ b/{}{}\n", path, tab, path, tab);
  size_t k = 0;
  while (k < ops.size()) {
    if (ops[k].kind == ' ') {
      ++k;
      continue;
    }
    // A hunk: from kContext lines before this change to kContext lines after the last change that is at most
    // 2*kContext unchanged lines away.
    size_t start = k >= kContext ? k - kContext : 0;
    size_t end = k;
    size_t last_change = k;
    while (end < ops.size()) {
      if (ops[end].kind != ' ') last_change = end;
      else if (end - last_change > 2 * kContext) break;
      ++end;
    }
    end = std::min(ops.size(), last_change + kContext + 1);
    size_t a_start = ops[start].a, b_start = ops[start].b, a_len = 0, b_len = 0;
    for (size_t i = start; i < end; ++i) {
      if (ops[i].kind != '+') ++a_len;
      if (ops[i].kind != '-') ++b_len;
    }
    auto range = [](size_t s, size_t len) {
      return len == 1 ? fmt::format("{}", s + 1) : fmt::format("{},{}", len == 0 ? s : s + 1, len);
    };
    out += fmt::format("@@ -{} +{} @@\n", range(a_start, a_len), range(b_start, b_len));
    for (size_t i = start; i < end; ++i) {
      const Op& op = ops[i];
      emit_line(out, op.kind, op.kind == '+' ? b[op.b] : a[op.a]);
    }
    k = end;
  }
  return out;
}

std::string diff_name(const std::optional<std::string>& disk, const std::string& shown) {
  std::error_code ec;
  if (!disk) return shown;
  const fs::path real = fs::canonical(*disk, ec);
  if (ec || real == fs::path(absolute_normal(*disk))) return shown;  // no link on the way
  const auto rel = path_below(real.string(), absolute_normal(fs::current_path(ec)));
  return rel && !ec ? *rel : real.string();
}

bool open_report_file(const std::string& path, const std::vector<std::string>& inputs, std::ofstream& out,
                      std::string* err) {
  std::error_code ec;
  if (fs::exists(path, ec))
    for (const std::string& in : inputs)
      if (fs::equivalent(path, in, ec)) {
        *err = fmt::format(
            "--output-file {}: that is {}, one of this run's input files, and the report would replace it (choose "
            "another file, or leave out -o for stdout)",
            path, in);
        return false;
      }
  out.open(path, std::ios::binary);
  if (!out) *err = fmt::format("{}: cannot write", path);
  return static_cast<bool>(out);
}

}  // namespace rrflint::cli
