// The robustness matrix (README "Exit codes and bad input"): every kind of bad input, each with its exit code and
// its message, run through the real binary. Nothing here may hang: run_rrflint_guarded kills a run after a generous
// 60 s (speed belongs in bench/, this only turns a hang into a failure).
//
// How each row gets its condition, since CI runs as root (where file modes stop neither reads nor writes):
//   unreadable files      setpriv drops to the user nobody for the run when the tests run as root
//   full disk             a 64 KiB tmpfs in a private mount namespace (unshare -m) when the system allows it,
//                         else a folder nobody may write to (run as nobody): both make the write fail
//   changed during a run  write_atomic (the writer seam) called directly with stale text
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "cli/cli.h"  // write_atomic (cli/fix.cc is built into the tests)
#include "tests/cli_util.h"

using namespace rrflint;
using namespace rrflint::test;

namespace {

const bool kRoot = ::geteuid() == 0;

// `timeout` turns a hang into exit 124 (coreutils, in every Debian).
Output run_guarded(const fs::path& cwd, const std::string& args, const std::string& stdin_text = "") {
  return run_rrflint(cwd, args, "timeout 60", stdin_text);
}

Output run_shell(const fs::path& cwd, const std::string& cmd);

// Runs rrflint as the user nobody (as root) or as this user. The tree and a copy of the binary are made readable to
// nobody: the build folder may not be (a clone under /root).
Output run_unprivileged(TempTree& t, const std::string& args) {
  ::chmod(t.root().c_str(), 0755);
  std::error_code ec;
  fs::create_directories(t / ".bin", ec);
  fs::copy_file(RRFLINT_BINARY, t / ".bin/rrflint", fs::copy_options::overwrite_existing, ec);
  ::chmod((t / ".bin").c_str(), 0755);
  ::chmod((t / ".bin/rrflint").c_str(), 0755);
  const std::string as = kRoot ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
  return run_shell(t.root(), "timeout 60 " + as + shell_quote((t / ".bin/rrflint").string()) + " " + args);
}

// Can this system run rrflint as nobody at all? Not where the file-system root itself is closed to other users
// (the chroot of shared/tools/fresh-debian.sh is a mktemp folder, mode 0700): there the tests that need another
// user say so and stop, and the same paths are covered through the reader seam ("unreadable files through the
// reader seam" below) and by the binary, FIFO and read-only rows.
bool can_drop_privileges(TempTree& t) {
  if (!kRoot) return true;
  const Output o = run_unprivileged(t, "--version");
  if (o.code != 0)
    RRFLINT_SKIPPED("cannot run rrflint as the user nobody here (" << o.err << "): this part is not run");
  return o.code == 0;
}

// Runs a shell command in `cwd`, capturing its output.
Output run_shell(const fs::path& cwd, const std::string& cmd) {
  TempTree io;
  const std::string out = (io / "out").string(), err = (io / "err").string();
  const int status = std::system(("cd " + shell_quote(cwd.string()) + " && (" + cmd + ") > " + shell_quote(out) +
                                  " 2> " + shell_quote(err) + " < /dev/null")
                                     .c_str());
  Output o;
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  o.out = io.read("out");
  o.err = io.read("err");
  return o;
}

// How many lines of `text` contain `needle`; how many lines `text` has.
size_t lines_count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t b = 0; b < text.size();) {
    size_t e = text.find('\n', b);
    if (e == std::string::npos) e = text.size();
    if (text.substr(b, e - b).find(needle) != std::string::npos) ++n;
    b = e + 1;
  }
  return n;
}
size_t lines_of_count(const std::string& text) { return lines_count(text, ""); }

std::string repeat(const std::string& s, size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (size_t i = 0; i < n; ++i) out += s;
  return out;
}

const std::string kGood = "M584 X0 Y1 Z2\nG28\n";

}  // namespace

TEST_CASE("matrix: nothing to lint is an error, never a pass", "[cli][matrix]") {
  TempTree t;
  fs::create_directories(t / "empty");
  t.write("nosys/readme.txt", "G1 X0\n");
  t.write("notes.txt", "G1 X0\n");
  // An empty folder, a folder without sys/ or any .g file, a named file that is not G-code, a missing path.
  for (const std::string path : {"empty", "nosys", "notes.txt", "missing"}) {
    DYNAMIC_SECTION(path) {
      auto o = run_guarded(t.root(), "check " + path);
      CHECK(o.code == 2);
      CHECK_FALSE(contains(o.out, "No problems found"));
      CHECK(contains(o.err, "error"));
      if (path != "missing") CHECK(contains(o.err, "no file was linted"));
    }
  }
  auto o = run_guarded(t.root(), "check notes.txt");
  CHECK(contains(o.err, "not a G-code file"));
  o = run_guarded(t.root(), "check empty");
  CHECK(contains(o.err, "empty: no G-code here"));
  // A directory where a file is expected: a config.g that is a folder makes no card either.
  fs::create_directories(t / "dircfg/sys/config.g");
  o = run_guarded(t.root(), "check dircfg");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "no file was linted"));
  // The same in JSON: nothing on stdout that a CI step could read as an empty, clean report.
  o = run_guarded(t.root(), "check empty --format json");
  CHECK(o.code == 2);
  CHECK(o.out.empty());
}

TEST_CASE("matrix: a card whose config.g cannot be linted is an error, the other cards are still reported",
          "[cli][matrix]") {
  TempTree t;
  t.write("good/sys/config.g", "M584 X0 Y1 Z2\nM9999\n");  // one RRF101 warning
  t.write("bin/sys/config.g", std::string("\x7f"
                                          "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0\x3e\0\x01\0\0\0",
                                          24) +
                                  repeat(std::string("\0\x01", 2), 64));
  t.write("utf16/sys/config.g", std::string("\xff\xfeM\0"
                                            "5\0"
                                            "8\0"
                                            "4\0 \0X\0"
                                            "0\0\n\0",
                                            18));
  t.write("empty/sys/config.g", "");
  SECTION("binary") {
    auto o = run_guarded(t.root(), "check bin");
    CHECK(o.code == 2);
    CHECK(contains(o.err, "bin/sys/config.g: cannot lint config.g: binary file"));
  }
  SECTION("UTF-16 is named as such") {
    auto o = run_guarded(t.root(), "check utf16");
    CHECK(o.code == 2);
    CHECK(contains(o.err, "UTF-16"));
  }
  SECTION("an empty config.g is linted, and said to be empty (RRF508), never a pass") {
    auto o = run_guarded(t.root(), "check empty --format concise");
    CHECK(o.code == 1);
    CHECK(contains(o.out, "empty/sys/config.g:1:1: error: config.g holds no command (the file is empty)"));
    CHECK(contains(o.out, "[RRF508 empty-config]"));
    // The same buffer on standard input, named config.g (a `cat missing | rrflint check …` pipe).
    o = run_guarded(t.root(), "check - --stdin-filename config.g --format concise", "");
    CHECK(o.code == 1);
    CHECK(contains(o.out, "RRF508"));
  }
  SECTION("several cards: 2 if any card could not be linted, and the others are still reported") {
    auto o = run_guarded(t.root(), "check good bin --format concise");
    CHECK(o.code == 2);
    CHECK(contains(o.out, "RRF101"));
    CHECK(contains(o.err, "cannot lint config.g"));
    o = run_guarded(t.root(), "check good empty");
    CHECK(o.code == 1);  // findings, and every card linted
    o = run_guarded(t.root(), "check good empty --fail-on error");
    CHECK(o.code == 1);  // the empty config.g is an error (RRF508)
    o = run_guarded(t.root(), "check good empty --fail-on error --ignore RRF508");
    CHECK(o.code == 0);
  }
}

TEST_CASE("matrix: a FIFO is never opened, named or found by walking", "[cli][matrix]") {
  TempTree t;
  fs::create_directories(t / "fifo/sys");
  REQUIRE(::mkfifo((t / "fifo/sys/config.g").c_str(), 0644) == 0);
  auto o = run_guarded(t.root(), "check fifo/sys/config.g");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "FIFO"));
  o = run_guarded(t.root(), "check fifo");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "cannot lint config.g: is a FIFO"));
  o = run_guarded(t.root(), "check .");  // a repository walk
  CHECK(o.code == 2);
  // A FIFO macro that config.g runs is a finding at the call.
  t.write("m/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"pipe.g\"\n");
  REQUIRE(::mkfifo((t / "m/sys/pipe.g").c_str(), 0644) == 0);
  o = run_guarded(t.root(), "check m --format concise");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "config.g:2:5: error: macro file '/sys/pipe.g' cannot be linted: is a FIFO"));
}

TEST_CASE("matrix: unreadable files (run as nobody)", "[cli][matrix]") {
  TempTree t;
  t.write("p/sys/config.g", kGood);
  t.write("q/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"tools.g\"\n");
  t.write("q/sys/tools.g", "M563 P0 D0\n");
  ::chmod((t / "p/sys/config.g").c_str(), 0);
  ::chmod((t / "q/sys/tools.g").c_str(), 0);
  if (!can_drop_privileges(t)) return;
  auto o = run_unprivileged(t, "check p");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "cannot lint config.g: permission denied"));
  o = run_unprivileged(t, "check q --format concise");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "macro file '/sys/tools.g' cannot be linted: permission denied [RRF506 unreadable-macro]"));
  o = run_unprivileged(t, "check q/sys/tools.g");  // named: an error of the run
  CHECK(o.code == 2);
  CHECK(contains(o.err, "permission denied"));
}

TEST_CASE("matrix: a folder that cannot be listed is an error, never a pass over what it holds (run as nobody)",
          "[cli][matrix]") {
  TempTree t;
  // A card whose sys/ can be entered but not listed: its config.g is never found, and only the macro would be linted.
  t.write("c/sys/config.g", "G10 P9 X0\nM584 X0 Y1 Z2\n");
  t.write("c/macros/park.g", "G1 X0\n");
  t.write("w/ok.g", "G1 X0\n");
  t.write("w/sub/h.g", "G1 X0\n");
  for (const char* d : {"c", "c/macros", "w"}) ::chmod((t / d).c_str(), 0755);
  ::chmod((t / "c/sys").c_str(), 0711);
  ::chmod((t / "w/sub").c_str(), 0);
  if (!can_drop_privileges(t)) return;
  auto o = run_unprivileged(t, "check c");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: c/sys: cannot list the folder: permission denied"));
  o = run_unprivileged(t, "check w");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: w/sub: cannot list the folder: permission denied"));
  // One that .gitignore leaves out is not walked anyway.
  t.write("w/.gitignore", "sub/\n");
  ::chmod((t / "w/.gitignore").c_str(), 0644);
  o = run_unprivileged(t, "check w");
  CHECK(o.code == 0);
  ::chmod((t / "c/sys").c_str(), 0755);
  ::chmod((t / "w/sub").c_str(), 0755);
}

TEST_CASE("matrix: binary and text with bad bytes", "[cli][matrix]") {
  TempTree t;
  t.write("c/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"bin.g\"\n");
  t.write("c/sys/bin.g", repeat(std::string("\0\x01\x02\x03", 4), 64));
  t.write("c/macros/blob.g", repeat(std::string("\0", 1), 100));
  auto o = run_guarded(t.root(), "check c --format concise");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "config.g:2:5: error: macro file '/sys/bin.g' cannot be linted: binary file"));
  // A binary macro nothing runs: a finding at the file itself.
  CHECK(contains(o.out, "macros/blob.g:1:1: error: file '/macros/blob.g' cannot be linted"));
  // Named on the command line: an error of the run, and no "No problems found".
  o = run_guarded(t.root(), "check c/sys/bin.g");
  CHECK(o.code == 2);
  CHECK_FALSE(contains(o.out, "No problems found"));
  // The boundary: up to 16 NUL bytes in the first 8 KiB of a text file are line ends (RRF100 each), more make it
  // binary.
  const std::string line = "G1 X1 Y1 F3000 ; a move, long enough to keep the control bytes under a tenth\n";
  t.write("n16/sys/config.g", "M584 X0 Y1 Z2\n" + repeat(std::string("G4 S0\0", 6) + line, 16));
  t.write("n17/sys/config.g", "M584 X0 Y1 Z2\n" + repeat(std::string("G4 S0\0", 6) + line, 17));
  o = run_guarded(t.root(), "check n16 --format concise");
  CHECK(o.code == 1);
  CHECK(lines_count(o.out, "NUL byte") == 16);
  o = run_guarded(t.root(), "check n17");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "binary file"));
}

TEST_CASE("matrix: huge and deep input is linted without a crash or a hang", "[cli][matrix]") {
  TempTree t;
  SECTION("a 10 MB single line") {
    t.write("p/sys/config.g", "M584 X0 Y1 Z2\nM550 P\"" + std::string(10u << 20, 'a') + "\"\n");
    auto o = run_guarded(t.root(), "check p --format concise");
    CHECK(o.code == 1);
    CHECK(contains(o.out, "RRF102 line-too-long"));
  }
  SECTION("a million lines") {
    t.write("p/sys/config.g", "M584 X0 Y1 Z2\n" + repeat("G1 X1 Y2 F3000\n", 1000000));
    auto o = run_guarded(t.root(), "check p");
    CHECK(o.code == 0);
    CHECK(contains(o.out, "No problems found in 1 file"));
  }
  SECTION("10,000 nested {") {
    t.write("p/sys/config.g", "M584 X0 Y1 Z2\nG1 X" + std::string(10000, '{') + "1" + std::string(10000, '}') + "\n");
    auto o = run_guarded(t.root(), "check p --format concise");
    CHECK((o.code == 0 || o.code == 1));
    CHECK(o.err.empty());
  }
  SECTION("10,000 nested if") {
    std::string text = "M584 X0 Y1 Z2\n";
    for (int i = 0; i < 10000; ++i) text += std::string(static_cast<size_t>(i), ' ') + "if true\n";
    text += std::string(10000, ' ') + "G4 S0\n";
    t.write("p/sys/config.g", text);
    auto o = run_guarded(t.root(), "check p --format concise");
    CHECK((o.code == 0 || o.code == 1));
    CHECK(o.err.empty());
  }
}

TEST_CASE("matrix: a graph cut at its node limit is said, not silent", "[cli][matrix]") {
  TempTree t;
  // 50 calls of a 10-line macro: 500 commands, past a limit lowered to 200 (RRFLINT_MAX_NODES, for tests).
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"calls.g\"\nM92 X80 X81\n");
  t.write("p/sys/calls.g", repeat("M98 P\"leaf.g\"\n", 50));
  t.write("p/sys/leaf.g", repeat("G4 P0\n", 10));
  auto cut = run_rrflint(t.root(), "check p --format concise", "RRFLINT_MAX_NODES=200 timeout 60");
  CHECK(contains(cut.err, "warning: p: the files run to more than 200 commands in all"));
  CHECK(contains(cut.out, "RRF116"));  // a file rule: it reads the whole file, wherever the graph stopped
  auto whole = run_guarded(t.root(), "check p --format concise");
  CHECK(!contains(whole.err, "commands in all"));
  CHECK(contains(whole.out, "RRF116"));
}

TEST_CASE("matrix: macro cycles and chains give one finding per cause", "[cli][matrix]") {
  TempTree t;
  t.write("cy/sys/config.g", "M98 P\"a.g\"\n");
  t.write("cy/sys/a.g", "M98 P\"b.g\"\n");
  t.write("cy/sys/b.g", "M98 P\"c.g\"\n");
  t.write("cy/sys/c.g", "M98 P\"a.g\"\n");
  auto o = run_guarded(t.root(), "check cy --firmware 3.5 --format json");
  CHECK(o.code == 1);
  CHECK(lines_count(o.out, "\"code\": \"RRF502\"") == 1);
  o = run_guarded(t.root(), "check cy --firmware 3.5");
  CHECK(lines_count(o.out, "runs the next file of the cycle here") ==
        2);  // a.g -> b.g, b.g -> c.g; c.g -> a.g is the finding
  std::string chain;
  t.write("ch/sys/config.g", "M98 P\"m0.g\"\n");
  for (int i = 0; i < 2000; ++i)
    t.write("ch/sys/m" + std::to_string(i) + ".g", "M98 P\"m" + std::to_string(i + 1) + ".g\"\n");
  t.write("ch/sys/m2000.g", "G4 S0\n");
  o = run_guarded(t.root(), "check ch --firmware 3.5 --format concise");
  CHECK(o.code == 1);
  CHECK(lines_count(o.out, "RRF503") == 1);
  CHECK(lines_of_count(o.out) == 1);
}

TEST_CASE("matrix: paths out of the root and symbolic link loops", "[cli][matrix]") {
  TempTree t;
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"../../etc/passwd\"\n");
  auto o = run_guarded(t.root(), "check p --format concise");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "RRF505 path-outside-root"));
  CHECK_FALSE(contains(o.out, "root:"));  // nothing of /etc/passwd was read
  t.write("l/sys/config.g", kGood);
  fs::create_directory_symlink("loop", t / "l/sys/loop");
  fs::create_symlink("b.g", t / "l/sys/a.g");
  fs::create_symlink("a.g", t / "l/sys/b.g");
  o = run_guarded(t.root(), "check l --format concise");
  CHECK(o.code == 0);
  o = run_guarded(t.root(), "check l/sys");
  CHECK(o.code == 0);
  o = run_guarded(t.root(), "check . --format concise");  // a walk over both: only p's finding
  CHECK(o.code == 1);
  CHECK(lines_of_count(o.out) == 1);
}

TEST_CASE("matrix: stdin and lone files", "[cli][matrix]") {
  TempTree t;
  // A name whose folder does not exist on disk is still linted: the buffer is always linted.
  auto o = run_guarded(t.root(), "check - --stdin-filename sys/homeall.g --format concise", "M9999\n");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "sys/homeall.g:1:1"));
  // stdin without a name, and a lone file: linted as a macro, and rrflint says so once, with the way to lint it
  // as config.g.
  o = run_guarded(t.root(), "check -", "M584 X0 Y1 Z2\n");
  CHECK(o.code == 0);
  CHECK(contains(o.err, "--stdin-filename config.g"));
  t.write("a.g", "G4 S0\n");
  t.write("b.g", "G4 S0\n");
  o = run_guarded(t.root(), "check a.g b.g");
  CHECK(o.code == 0);
  CHECK(lines_count(o.err, "note:") == 1);
  o = run_guarded(t.root(), "check - --stdin-filename config.g --format concise", "M9999\n");
  CHECK(o.code == 1);
  CHECK_FALSE(contains(o.err, "note:"));
}

TEST_CASE("matrix: standard input that cannot be read is an I/O error, not an empty file", "[cli][matrix]") {
  TempTree t;
  t.write("sys/config.g", kGood);
  // Standard input redirected from a folder: read() fails with EISDIR. The run must not pass over nothing.
  const std::string out = (t.root() / "out.txt").string();
  const std::string cmd = "cd " + shell_quote(t.root().string()) + " && " + shell_quote(RRFLINT_BINARY) +
                          " check - --stdin-filename sys/config.g < sys > " + shell_quote(out) + " 2>&1";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 2);
  std::ifstream f(out);
  std::stringstream ss;
  ss << f.rdbuf();
  CHECK(contains(ss.str(), "cannot read standard input"));
}

TEST_CASE("matrix: standard input redirected from a large file is mapped, and read on from where it stands",
          "[cli][matrix]") {
  // 4 MB and more, at offset 0: mapped (frontend/disk.cc map_standard_input). After another program read part of
  // the descriptor: read from there on, never mapped from the file's start.
  TempTree t;
  std::string body = kGood;
  while (body.size() < (size_t{5} << 20)) body += "; padding: a comment line that RRF skips\n";
  body += "M9999\n";
  t.write("body.g", body);
  t.write("head.g", "M9998\n" + body);  // a 6-byte line first, read away below
  auto lint = [&](const std::string& input) {
    const std::string out = (t.root() / "out.txt").string();
    const std::string cmd =
        "cd " + shell_quote(t.root().string()) + " && " + input + " > " + shell_quote(out) + " 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream f(out);
    std::stringstream ss;
    ss << f.rdbuf();
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str());
  };
  const std::string check = shell_quote(RRFLINT_BINARY) + " check --format concise --stdin-filename sys/config.g -";
  const auto mapped = lint(check + " < body.g");
  const auto piped = lint("cat body.g | " + check);
  CHECK(mapped.first == 1);
  CHECK(contains(mapped.second, "config.g:" + std::to_string(std::count(body.begin(), body.end(), '\n')) + ":1"));
  CHECK(contains(mapped.second, "M9999"));
  CHECK(mapped == piped);
  const auto after_head = lint("{ head -c 6 >/dev/null; " + check + "; } < head.g");
  CHECK(after_head == mapped);
  CHECK(!contains(after_head.second, "M9998"));
}

TEST_CASE(
    "matrix: exclusions: a folder named on purpose is linted, --force-exclude leaves it out, and exits 0 only "
    "when every path was left out",
    "[cli][matrix][walk]") {
  TempTree t;
  t.write(".gitignore", "old/\n");
  t.write("old/sys/config.g", "M584 X0 Y1 Z2\nM9999\n");
  t.write("new/sys/config.g", kGood);
  t.write(".rrflint.toml", "exclude = [\"draft\"]\n");
  t.write("draft/sys/config.g", "M584 X0 Y1 Z2\nM9999\n");
  if (std::system(("git -C " + shell_quote(t.root().string()) + " init -q 2>/dev/null").c_str()) != 0)
    t.write(".git/HEAD", "");
  auto o = run_guarded(t.root(), "check old --format concise");  // gitignored, named explicitly: linted
  CHECK(o.code == 1);
  CHECK(contains(o.out, "RRF101"));
  o = run_guarded(t.root(), "check draft --format concise");  // excluded, named explicitly: linted
  CHECK(o.code == 1);
  o = run_guarded(t.root(), "check old draft --force-exclude");
  CHECK(o.code == 0);
  CHECK(contains(o.err, "every path given is excluded"));
  CHECK_FALSE(contains(o.out, "No problems found"));
  o = run_guarded(t.root(), "check old/sys/config.g --force-exclude");
  CHECK(o.code == 0);
  o = run_guarded(t.root(), "check old new --force-exclude");
  CHECK(o.code == 0);
  CHECK(contains(o.out, "No problems found in 1 file"));
  // A walk whose every file is excluded lints nothing: an error, since nothing was named to be left out.
  t.write("only/draft/sys/config.g", "M9999\n");
  t.write("only/.rrflint.toml", "exclude = [\"draft\"]\n");
  o = run_guarded(t.root(), "check only");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "excluded"));
}

TEST_CASE("matrix: --firmware spellings and unknown commands", "[cli][matrix]") {
  TempTree t;
  t.write("p/sys/config.g", kGood);
  for (const std::string v : {"3.5", "3.5.0beta2", "3.5.0-beta.2", "3.01-RC3", "2.02RC2", "3.4.6", "1.0"}) {
    DYNAMIC_SECTION(v) { CHECK(run_guarded(t.root(), "check p --firmware " + v).code == 0); }
  }
  auto o = run_guarded(t.root(), "check p --firmware 4.2");
  CHECK(o.code == 0);
  CHECK(contains(o.err, "newer than the newest version rrflint knows"));
  for (const std::string v : {"banana", "0.9", "3.x"}) {
    DYNAMIC_SECTION("bad " << v) {
      o = run_guarded(t.root(), "check p --firmware " + v);
      CHECK(o.code == 2);
      CHECK(contains(o.err, "known: 1.x, 2.0x, 3.0 to"));
    }
  }
  t.write(".rrflint.toml", "firmware = \"3.9.1\"\n");
  o = run_guarded(t.root(), "check p");
  CHECK(o.code == 0);
  CHECK(contains(o.err, "newer than the newest version"));
  t.write(".rrflint.toml", "firmware = \"three\"\n");
  CHECK(run_guarded(t.root(), "check p").code == 2);
  o = run_guarded(t.root(), "explain RRF301");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "unknown command 'explain'"));
  CHECK(contains(o.err, "check"));
  CHECK(contains(o.err, "rule"));
  o = run_guarded(t.root(), "--select RRF301 check p");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "unknown option '--select' before a command"));
  CHECK(run_guarded(t.root(), "--version").code == 0);
}

TEST_CASE("matrix: --fix never writes a read-only file, through a link out of the root, or over a full disk",
          "[cli][matrix][fix]") {
  TempTree t;
  const std::string before = "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\nM9999\n";
  SECTION("read-only") {
    t.write("p/sys/config.g", before);
    ::chmod((t / "p/sys/config.g").c_str(), 0444);
    auto o = run_guarded(t.root(), "check p --fix --format concise");
    CHECK(o.code == 2);
    CHECK(t.read("p/sys/config.g") == before);
    CHECK(contains(o.err, "read-only: not written"));
    CHECK_FALSE(contains(o.out, "Fixed"));
    CHECK(contains(o.out, "RRF900"));  // the finding the fix would have removed is still reported
    struct stat st {};
    ::stat((t / "p/sys/config.g").c_str(), &st);
    CHECK((st.st_mode & 0777) == 0444);
  }
  SECTION("a link out of the root") {
    t.write("outside/config.g", before);
    fs::create_directories(t / "p/sys");
    fs::create_symlink(t / "outside/config.g", t / "p/sys/config.g");
    auto o = run_guarded(t.root(), "check p --fix");
    CHECK(o.code == 2);
    CHECK(contains(o.err, "outside the linted folder"));
    CHECK(t.read("outside/config.g") == before);
    CHECK(fs::is_symlink(t / "p/sys/config.g"));
  }
  SECTION("as another user, a file it could not write in place") {
    t.write("p/sys/config.g", before);
    ::chmod((t / "p").c_str(), 0777);
    ::chmod((t / "p/sys").c_str(), 0777);  // the folder would allow a rename
    ::chmod((t / "p/sys/config.g").c_str(), 0644);
    if (kRoot && can_drop_privileges(t)) {
      auto o = run_unprivileged(t, "check p --fix");
      CHECK(o.code == 2);
      CHECK(contains(o.err, "not written"));
      CHECK(t.read("p/sys/config.g") == before);
    }
  }
  SECTION("a full disk") {
    // A 64 KiB tmpfs in a private mount namespace, filled up; else a folder nobody may write to, run as nobody.
    const bool tmpfs = kRoot && std::system("unshare -m true 2>/dev/null") == 0;
    t.write("p/sys/config.g", before);
    Output o;
    if (tmpfs) {
      const std::string script = "mount -t tmpfs -o size=64k tmpfs p/sys && printf '%s' " + shell_quote(before) +
                                 " > p/sys/config.g && (dd if=/dev/zero of=p/sys/fill bs=4k 2>/dev/null; true) && " +
                                 shell_quote(RRFLINT_BINARY) +
                                 " check p --fix --format concise; echo \"rc=$?\"; cat p/sys/config.g";
      o = run_shell(t.root(), "timeout 60 unshare -m sh -c " + shell_quote(script));
      CHECK(contains(o.out, "rc=2"));
      CHECK(contains(o.err, "No space left on device"));
    } else {
      if (!can_drop_privileges(t)) return;
      ::chmod((t / "p/sys").c_str(), 0555);
      ::chmod((t / "p/sys/config.g").c_str(), 0666);
      o = run_unprivileged(t, "check p --fix --format concise");
      CHECK(o.code == 2);
      CHECK(contains(o.err, "cannot create a temporary file"));
      ::chmod((t / "p/sys").c_str(), 0755);
    }
    CHECK(contains(o.err, "not written"));
    CHECK(contains(o.out, before));  // the file on the (full) disk is whole
    CHECK_FALSE(contains(o.out, "Fixed"));
    CHECK(contains(o.out, "RRF900"));
  }
}

TEST_CASE("write_atomic: refuses a file that changed since it was read, and keeps line endings and modes",
          "[cli][matrix][fix]") {
  TempTree t;
  const fs::path p = t.write("sys/config.g", "G4 S0\r\nM9999");
  ::chmod(p.c_str(), 0640);
  std::string err;
  CHECK_FALSE(cli::write_atomic(p, "something else", "new", {t.root()}, &err));
  CHECK(contains(err, "changed on disk"));
  CHECK(t.read("sys/config.g") == "G4 S0\r\nM9999");
  CHECK(cli::write_atomic(p, "G4 S0\r\nM9999", "G4 S1\r\nM9999", {t.root()}, &err));
  CHECK(t.read("sys/config.g") == "G4 S1\r\nM9999");  // no final newline added
  struct stat st {};
  ::stat(p.c_str(), &st);
  CHECK((st.st_mode & 0777) == 0640);
  for (const auto& e : fs::directory_iterator(t / "sys"))
    CHECK_FALSE(contains(e.path().filename().string(), ".rrflint-"));
}

TEST_CASE("apply_fixes: overlapping fixes are never applied together, a file's line ending is kept",
          "[cli][matrix][fix]") {
  SourceManager sm;
  const SourceFile& f = sm.add("config.g", "/sys/config.g", TextBuffer(std::string("G1 X0 Y0\r\nG1 X1\r\n")));
  auto diag = [&](uint32_t b, uint32_t e, std::string with) {
    Diagnostic d;
    d.loc = Location{f.id(), Span{b, e}};
    d.fix = Fix{"edit", Applicability::Safe, {Edit{Location{f.id(), Span{b, e}}, std::move(with)}}};
    return d;
  };
  // Two fixes over "X0" (3..5) and "X0 Y0" (3..8): only the first is applied in this round; an insertion of a
  // new line at the end gets the file's CRLF.
  const std::vector<Diagnostic> diags = {diag(3, 5, "X5"), diag(3, 8, "Z9"), diag(17, 17, "M400\n")};
  std::map<FileId, std::string> texts;
  std::map<FileId, size_t> per_file;
  const size_t n = cli::apply_fixes(
      sm, diags, cli::FixOptions{}, [](FileId) { return true; }, texts, &per_file);
  CHECK(n == 2);
  CHECK(per_file[f.id()] == 2);
  CHECK(texts[f.id()] == "G1 X5 Y0\r\nG1 X1\r\nM400\r\n");
  // A file the run may not write gets no edit at all.
  texts.clear();
  CHECK(cli::apply_fixes(
            sm, diags, cli::FixOptions{}, [](FileId) { return false; }, texts) == 0);
  CHECK(texts.empty());
}

// Found by tests/fuzz/fuzz_fix.cc: the CR-to-LF fix of a CR-only file was written back with CRs (the file's own
// line ending), so --fix reported fixes round after round and changed nothing.
TEST_CASE("apply_fixes: an edit of line endings writes the ones it says, not the file's", "[cli][matrix][fix]") {
  SourceManager sm;
  const SourceFile& f = sm.add("config.g", "/sys/config.g", TextBuffer(std::string("M83\rG4 S1\r")));
  Diagnostic d;
  d.loc = Location{f.id(), Span{3, 4}};
  d.fix = Fix{"replace CR line endings with LF",
              Applicability::Safe,
              {Edit{Location{f.id(), Span{3, 4}}, "\n"}, Edit{Location{f.id(), Span{9, 10}}, "\n"},
               Edit{Location{f.id(), Span{0, 0}}, "; note\n"}}};
  std::map<FileId, std::string> texts;
  CHECK(cli::apply_fixes(
            sm, {d}, cli::FixOptions{}, [](FileId) { return true; }, texts) == 1);
  // The line endings become LF; the inserted line still gets the file's CR.
  CHECK(texts[f.id()] == "; note\rM83\nG4 S1\n");
}

TEST_CASE("matrix: --fix writes only the files that were linted, and keeps their owner", "[cli][matrix][fix]") {
  TempTree t;
  const std::string fixable = "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\n";
  t.write("p/sys/config.g", fixable);
  t.write("p/sys/homeall.g", "G1 X0 ; rrflint: disable=unknown-command\n");
  // Only the named file is linted and reported, so only it is fixed.
  auto o = run_guarded(t.root(), "check p/sys/homeall.g --fix");
  CHECK(o.code == 0);
  CHECK(t.read("p/sys/homeall.g") == "G1 X0\n");
  CHECK(t.read("p/sys/config.g") == fixable);
  if (kRoot) {
    REQUIRE(::chown((t / "p/sys/config.g").c_str(), 65534, 65534) == 0);
    o = run_guarded(t.root(), "check p --fix");
    CHECK(o.code == 0);
    CHECK(t.read("p/sys/config.g") == "M584 X0 Y1 Z2\nG1 X0\n");
    struct stat st {};
    ::stat((t / "p/sys/config.g").c_str(), &st);
    CHECK(st.st_uid == 65534);
    CHECK(st.st_gid == 65534);
  }
}

TEST_CASE("matrix: the report is never written over a file the run reads, -o - is stdout", "[cli][matrix]") {
  TempTree t;
  const std::string config = "M584 X0 Y1 Z2\nG10 P0 X1\nM98 P\"m.g\"\n", macro = "G28\n",
                    toml = "fail-on = \"error\"\n";
  t.write("p/sys/config.g", config);
  t.write("p/sys/m.g", macro);
  t.write("p/.rrflint.toml", toml);
  fs::create_symlink("sys/config.g", t / "p/link");
  // config.g, a macro it runs (named another way), the settings file, a link to config.g, and the file stdin stands
  // for: each is refused (exit 2) and keeps its bytes, with --fix too.
  for (const std::string args :
       {"check p -o p/sys/config.g", "check p -o p/sys/../sys/m.g", "check p -o p/.rrflint.toml", "check p -o p/link",
        "check p/sys/config.g --fix -o p/link", "check --stdin-filename p/sys/config.g - -o p/sys/config.g"}) {
    INFO(args);
    const auto o = run_rrflint(t.root(), args, "", config);
    CHECK(o.code == 2);
    CHECK(contains(o.err, "one of this run's input files, and the report would replace it"));
    CHECK(t.read("p/sys/config.g") == config);
    CHECK(t.read("p/sys/m.g") == macro);
    CHECK(t.read("p/.rrflint.toml") == toml);
  }
  // Another file takes the report; '-' is stdout, not a file named '-'.
  auto o = run_rrflint(t.root(), "check p -o report.txt");
  CHECK(o.code == 1);
  CHECK(contains(t.read("report.txt"), "g10-tool-before-definition"));
  o = run_rrflint(t.root(), "check p --format json -o -");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "\"g10-tool-before-definition\""));
  CHECK(!fs::exists(t / "-"));
}

TEST_CASE("matrix: output that cannot be written is an I/O error (exit 2), never a pass", "[cli][matrix]") {
  if (!fs::exists("/dev/full")) {
    RRFLINT_SKIPPED("no /dev/full here: not tested");
    return;
  }
  TempTree t;
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\nG10 P0 X1\n");
  t.write("clean/sys/config.g", "M584 X0 Y1 Z2\n");
  // rrflint with stdout on a full disk: its exit code and stderr.
  auto to_full = [&](const std::string& args) {
    const std::string err = (t / "err.txt").string();
    const int status = std::system(("cd " + shell_quote(t.root().string()) + " && " + shell_quote(RRFLINT_BINARY) +
                                    " " + args + " > /dev/full 2> " + shell_quote(err))
                                       .c_str());
    return std::pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, t.read("err.txt"));
  };
  // A full disk: the report to a file and to stdout, with findings, with none and with --exit-zero; the other
  // subcommands' output.
  for (const std::string args : {"check p -o /dev/full", "check p", "check p --exit-zero", "check clean",
                                 "check clean --format json -o /dev/full", "check --format sarif p", "model p",
                                 "rule RRF301", "config p", "--help", "--version"}) {
    INFO(args);
    const auto [code, err] = to_full(args);
    CHECK(code == 2);
    CHECK(contains(err, "cannot write the"));
  }
  // What writes nothing does not fail: --diff with no fix to show.
  CHECK(to_full("check clean --diff").first == 0);
}

TEST_CASE("matrix: unreadable files through the reader seam: config.g is a load problem, a macro a finding",
          "[cli][matrix]") {
  // A reader that answers "permission denied" for some files, as the disk reader does for a mode-000 file.
  struct Denying : MemoryReader {
    std::set<std::string> denied;
    ReadResult read(std::string_view sd) override {
      if (!denied.count(std::string(sd))) return MemoryReader::read(sd);
      ReadResult r;
      r.status = ReadResult::Status::Error;
      r.error = "permission denied";
      r.display = std::string(sd).substr(1);
      return r;
    }
  } reader;
  reader.add("/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"tools.g\"\n");
  reader.add("/sys/tools.g", "M563 P0 D0\n");
  reader.denied = {"/sys/tools.g"};
  SourceManager sm;
  LintOptions lo;
  lo.firmware = Version(3, 5, 0);
  MachineResult r = lint_machine(sm, reader, builtin_rules(), lo);
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].code == "RRF506");
  CHECK(r.diagnostics[0].message == "macro file '/sys/tools.g' cannot be linted: permission denied");
  reader.denied = {"/sys/config.g"};
  SourceManager sm2;
  r = lint_machine(sm2, reader, builtin_rules(), lo);
  REQUIRE(r.machine->problems().size() == 1);
  CHECK(r.machine->problems()[0].sd_path == "/sys/config.g");  // the CLI makes this an error of the card (exit 2)
  CHECK(r.machine->unit_count() == 1);                         // tools.g is still linted, as an entry
}

// config.g alone, for RRF 3.5, with one rule.
static MachineResult lint_one_rule(SourceManager& sm, const std::string& config, const std::string& rule) {
  MemoryReader reader;
  reader.add("/sys/config.g", config);
  LintOptions lo;
  lo.firmware = Version(3, 5, 0);
  lo.select = {rule};
  return lint_machine(sm, reader, builtin_rules(), lo);
}

TEST_CASE("no fix rewrites a command that does not parse (found by fuzz_fix)", "[robustness][fix]") {
  // RRF307's M568 copied `P{pa@am.T}` from a G10 whose expression does not parse: the fix added a second syntax
  // error. The finding stays; the fix is not offered for such a command. The G10 beside it keeps its fix.
  SourceManager sm;
  MachineResult r =
      lint_one_rule(sm, "M584 X0 Y1 Z2 E3\nM563 P0 D0\nM563 P1 D0\nG10 P{pa@am.T} S200\nG10 P1 S200\n", "RRF307");
  REQUIRE(r.diagnostics.size() == 2);
  CHECK(r.diagnostics[0].code == "RRF307");
  CHECK_FALSE(r.diagnostics[0].fix);
  REQUIRE(r.diagnostics[1].fix);
  CHECK(r.diagnostics[1].fix->title == "replace with 'M568 P1 S200'");
  // Nor one that a ';' cuts open (RRF113, no parse error): the moved `S{…` would lose its closing '}'.
  SourceManager sm2;
  r = lint_one_rule(sm2, "M584 X0 Y1 Z2 E3\nM563 P0 D0\nG10 P0 X1 S{global.t ; standby }\n", "RRF307");
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].code == "RRF307");
  CHECK_FALSE(r.diagnostics[0].fix);
  // RRF220's one M569 per driver copied an unterminated string (`C"driver`) or an expression a ';' cuts open onto
  // every new line (found by the CI's fuzz smoke): a new syntax error per driver. The M569 after them keeps its fix.
  SourceManager sm3;
  r = lint_one_rule(sm3, "M584 X0 Y1 Z2:3 E4\nM569 P0.2:0.3 S1 C\"driver\nM569 P0:1 S{1 ; note\nM569 P2:3 S1\n",
                    "RRF220");
  REQUIRE(r.diagnostics.size() == 3);
  CHECK_FALSE(r.diagnostics[0].fix);
  CHECK_FALSE(r.diagnostics[1].fix);
  REQUIRE(r.diagnostics[2].fix);
  CHECK(r.diagnostics[2].fix->title == "write one M569 per driver (2)");
}

TEST_CASE("a fix on the last line of a file with mixed line endings uses the usual one", "[robustness][fix]") {
  // The last line has no ending of its own: a line a fix adds after it takes the ending most lines have, the one
  // --fix also writes for a "\n" in a fix's text (SourceFile::usual_ending). RRF220 took CRLF when any line had
  // it, RRF307 the line before's.
  auto edits = [](const char* text, const char* rule) {
    SourceManager sm;
    MachineResult r = lint_one_rule(sm, text, rule);
    std::vector<std::string> out;
    for (const Diagnostic& d : r.diagnostics)
      if (d.fix)
        for (const Edit& e : d.fix->edits) out.push_back(e.replacement);
    return out;
  };
  CHECK(edits("M584 X0 Y1 Z2:3 E4\r\nM569 P0 S1\nM569 P1 S1\nM569 P2:3 S1", "RRF220") ==
        std::vector<std::string>{"M569 P2 S1\nM569 P3 S1"});
  CHECK(edits("M584 X0 Y1 Z2:3 E4\r\nM569 P0 S1\r\nM569 P1 S1\nM569 P2:3 S1", "RRF220") ==
        std::vector<std::string>{"M569 P2 S1\r\nM569 P3 S1"});
  CHECK(edits("M584 X0 Y1 Z2 E3\nM563 P0 D0\nM563 P1 D0\r\n  G10 P1 X1 S200", "RRF307") ==
        std::vector<std::string>{"", "\n  M568 P1 S200"});
  CHECK(edits("M584 X0 Y1 Z2 E3\r\nM563 P0 D0\r\nM563 P1 D0\n  G10 P1 X1 S200", "RRF307") ==
        std::vector<std::string>{"", "\r\n  M568 P1 S200"});
}

TEST_CASE("no fix edits inside a line whose checksum it would break", "[robustness][fix]") {
  // `N5 G10 P1 S200*29` runs while its checksum matches; RRF307's M568 in place of the G10 would break the checksum
  // and RRF would drop the line silently. Every rule's fix is withdrawn there (lint_machine); the same G10 with a
  // line number and no checksum keeps its fix.
  SourceManager sm;
  MachineResult r =
      lint_one_rule(sm, "M584 X0 Y1 Z2 E3\nM563 P0 D0\nM563 P1 D0\nN5 G10 P1 S200*29\nN6 G10 P0 S200\n", "RRF307");
  REQUIRE(r.diagnostics.size() == 2);
  CHECK(r.diagnostics[0].code == "RRF307");
  CHECK(r.diagnostics[0].loc.span.begin == 42);  // the checksummed G10
  CHECK_FALSE(r.diagnostics[0].fix);
  REQUIRE(r.diagnostics[1].fix);
  CHECK(r.diagnostics[1].fix->title == "replace with 'M568 P0 S200'");
}

TEST_CASE("one round of --fix moves a run of a tool's lines after its M563 (found by fuzz_fix)", "[robustness][fix]") {
  // RRF301 moved one line per round (each line's fix inserted at the same point, which apply_fixes takes one at a
  // time): twelve G10 lines for tool 0 needed twelve rounds, past --fix's ten. The first line's fix now moves the
  // run, in order, and the lines of another tool in between stay where they are.
  std::string config = "M584 X0 Y1 Z2 E3:4\n";
  for (int i = 0; i < 12; ++i) config += fmt::format("G10 P0 X{} Y0 Z0\n", i);
  config += "G10 P7 X0 Y0 Z0\nM563 P0 D0\nM563 P1 D1\n";
  SourceManager sm;
  MachineResult r = lint_one_rule(sm, config, "RRF301");
  REQUIRE(r.diagnostics.size() == 13);
  cli::FixOptions fo;
  fo.unsafe = true;
  std::map<FileId, std::string> texts;
  CHECK(cli::apply_fixes(
            sm, r.diagnostics, fo, [](FileId) { return true; }, texts) == 1);
  REQUIRE(texts.size() == 1);
  std::string want = "M584 X0 Y1 Z2 E3:4\nG10 P7 X0 Y0 Z0\nM563 P0 D0\n";
  for (int i = 0; i < 12; ++i) want += fmt::format("G10 P0 X{} Y0 Z0\n", i);
  want += "M563 P1 D1\n";
  CHECK(texts.begin()->second == want);
}

// Rules with broken fixes, for the safety net of --fix's rounds (cli::run_fix_rounds). TST901 "fixes" `G1 X1` into
// `G1 X{1`, an expression that never closes; TST902 turns M80 into M81, a fix that is fine; TST903 appends to
// every comment, so its fixes never settle.
namespace {
template <class Edit_of>
void fix_each_line(const FileContext& ctx, Sink& out, const RuleMeta& meta, std::string_view starts, Edit_of edit_of) {
  const ParsedFile& p = ctx.parsed();
  for (size_t i = 0; i < p.lines.size(); ++i) {
    const Line l = p.lines[i];
    const std::string_view whole = p.text(l.span);
    if (whole.substr(0, starts.size()) != starts) continue;
    out.report(meta, ctx.at(l.span), "test").fix(Fix::safe("test", edit_of(ctx, l)));
  }
}
const Rule kBreaksSyntax{RuleMeta{"TST901", "test-breaks-syntax", Severity::Warning, true, FixAvailability::Always},
                         [](const FileContext& ctx, Sink& out) {
                           fix_each_line(ctx, out, kBreaksSyntax.meta, "G1 X1", [](const FileContext& c, Line l) {
                             return Edit::insert(c.at(Span{l.code.begin + 4, l.code.begin + 4}), "{");
                           });
                         }};
const Rule kGoodFix{RuleMeta{"TST902", "test-good-fix", Severity::Warning, true, FixAvailability::Always},
                    [](const FileContext& ctx, Sink& out) {
                      fix_each_line(ctx, out, kGoodFix.meta, "M80", [](const FileContext& c, Line l) {
                        return Edit::replace(c.at(Span{l.code.begin, l.code.begin + 3}), "M81");
                      });
                    }};
const Rule kNeverSettles{RuleMeta{"TST903", "test-never-settles", Severity::Warning, true, FixAvailability::Always},
                         [](const FileContext& ctx, Sink& out) {
                           fix_each_line(ctx, out, kNeverSettles.meta, ";", [](const FileContext& c, Line l) {
                             return Edit::insert(c.at(Span{l.span.end, l.span.end}), "!");
                           });
                         }};

struct FixRoundsRun {
  MemoryReader reader;
  SourceManager sm;
  RuleSet rules;
  std::map<std::string, std::string> texts;
  MachineResult r;
  explicit FixRoundsRun(std::vector<const Rule*> rs, std::map<std::string, std::string> files)
      : rules(std::move(rs)), texts(std::move(files)) {
    r = relint();
  }
  MachineResult relint() {
    reader = MemoryReader();
    for (const auto& [sd, text] : texts) reader.add(sd, text);
    return lint_machine(sm, reader, rules, LintOptions{});
  }
  cli::FixRounds run(int max_rounds = 10) {
    cli::FixOptions fo;
    fo.max_rounds = max_rounds;
    return cli::run_fix_rounds(
        sm, r, fo, [](FileId) { return true; },
        [&](const std::string& sd, const std::string& text) { texts[sd] = text; }, [&] { return relint(); });
  }
};
}  // namespace

TEST_CASE("fix rounds: a round that makes a syntax error is undone, and that file is fixed no further", "[cli][fix]") {
  FixRoundsRun run({&kBreaksSyntax, &kGoodFix},
                   {{"/sys/config.g", "M80\nG1 X1\nM98 P\"m.g\"\n"}, {"/sys/m.g", "M80\nG1 Y2\n"}});
  const cli::FixRounds f = run.run();
  // config.g: the broken fix and the good one were in the same round: both undone, the file left as it was.
  CHECK(run.texts["/sys/config.g"] == "M80\nG1 X1\nM98 P\"m.g\"\n");
  CHECK(f.current.count("/sys/config.g") == 0);
  REQUIRE(f.reverted.size() == 1);
  CHECK(f.reverted.begin()->first == "/sys/config.g");
  CHECK(f.reverted.begin()->second == std::vector<std::string>{"TST901", "TST902"});
  // m.g: its good fix, undone with the round, is applied again in the next one and kept.
  CHECK(run.texts["/sys/m.g"] == "M81\nG1 Y2\n");
  CHECK(f.current.at("/sys/m.g") == "M81\nG1 Y2\n");
  CHECK(f.fixed == 1);
  CHECK(f.settled);
  // The findings returned are those of the texts as they are: config.g's two still stand.
  size_t in_config = 0;
  for (const Diagnostic& d : run.r.diagnostics) in_config += run.sm.get(d.loc.file).sd_path() == "/sys/config.g";
  CHECK(in_config == 2);
}

TEST_CASE("fix rounds: say when the fixes have not settled after the last round", "[cli][fix]") {
  FixRoundsRun run({&kNeverSettles}, {{"/sys/config.g", "; a\nG28\n"}});
  const cli::FixRounds f = run.run(3);
  CHECK(run.texts["/sys/config.g"] == "; a!!!\nG28\n");
  CHECK(f.fixed == 3);
  CHECK_FALSE(f.settled);
  CHECK(f.reverted.empty());
  // Fixes that settle say so.
  FixRoundsRun good({&kGoodFix}, {{"/sys/config.g", "M80\nM80\n"}});
  const cli::FixRounds g = good.run(3);
  CHECK(good.texts["/sys/config.g"] == "M81\nM81\n");
  CHECK(g.fixed == 2);
  CHECK(g.settled);
}

TEST_CASE("fix rounds: the editor's fix-all is checked the same way (parses_worse)", "[cli][fix]") {
  const SourceFile clean(0, "config.g", "/sys/config.g", TextBuffer(std::string("G1 X1\n")));
  CHECK(cli::parses_worse(clean, "G1 X{1\n"));
  CHECK(cli::parses_worse(clean, "G1 X{global.a ; b }\n"));  // an expression a ';' cuts open
  CHECK_FALSE(cli::parses_worse(clean, "G1 X2\n"));
  const SourceFile broken(0, "config.g", "/sys/config.g", TextBuffer(std::string("G1 X{1\nM80\n")));
  CHECK_FALSE(cli::parses_worse(broken, "G1 X{1\nM81\n"));  // no worse than it was
  CHECK_FALSE(cli::parses_worse(broken, "G1 X1\nM81\n"));
}

namespace {
// `text` with every word of 4 or more letters, digits, '_' and '.' (names, paths, numbers after a letter) and
// every quoted string made `n` bytes long by repeating it.
std::string lengthened(std::string_view text, size_t n) {
  auto word_byte = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
  std::string out;
  for (size_t i = 0; i < text.size();) {
    size_t e = i;
    if (text[i] == '"') {
      e = text.find_first_of("\"\n", i + 1);
      if (e == std::string_view::npos || text[e] != '"' || e == i + 1) {
        out += text[i++];
        continue;
      }
      const std::string_view inner = text.substr(i + 1, e - i - 1);
      out += '"';
      while (out.size() < n + i) out += inner;  // about n bytes
      out += '"';
      i = e + 1;
      continue;
    }
    while (e < text.size() && word_byte(text[e])) ++e;
    if (e - i >= 4) {
      const std::string_view w = text.substr(i, e - i);
      for (size_t k = 0; k < n; k += w.size()) out += w;
      i = e;
    } else if (e > i) {
      out += text.substr(i, e - i);
      i = e;
    } else {
      out += text[i++];
    }
  }
  return out;
}
}  // namespace

TEST_CASE("a finding quotes a long word short: every fixture with its words and strings 3,000 bytes long",
          "[robustness]") {
  // Found by lint runs over such files: eight rules quoted a command word, a value, a path or a name whole (a
  // 60,000-byte message for a long global name; a fix titled with 6,000 bytes). What a message quotes from the
  // file is cut (clip(): 40 bytes, 120 for a path).
  size_t files = 0, findings = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(RRFLINT_SOURCE_DIR) / "fixtures")) {
    if (!e.is_regular_file() || e.path().extension() != ".g") continue;
    std::ifstream in(e.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    MemoryReader reader;
    reader.add("/sys/config.g", lengthened(text, 3000));
    SourceManager sm;
    const MachineResult r = lint_machine(sm, reader, builtin_rules(), LintOptions{});
    ++files;
    for (const Diagnostic& d : r.diagnostics) {
      ++findings;
      INFO(e.path().string() << ": " << d.code << ": " << d.message.substr(0, 200));
      CHECK(d.message.size() <= 400);
      for (const Note& n : d.notes) CHECK(n.message.size() <= 400);
      if (d.fix) CHECK(d.fix->title.size() <= 200);
    }
  }
  CHECK(files > 300);
  CHECK(findings > 1000);
}

TEST_CASE("RRF301's fix gives up past 256 other tools' lines between the G10 and its M563", "[robustness][fix]") {
  // A config of thousands of tools asked, for each G10 before its M563, every node between and every later M563
  // (seconds for 40,000 lines). The M563s are now indexed by tool, and the lines between found from the code
  // index; more than 256 of them between, and the move is not offered (the finding stands).
  auto config_with = [](int others) {
    std::string config = "M584 X0 Y1 Z2 E3\nG10 P7 X1 Y1 Z0\n";
    for (int i = 0; i < others; ++i) config += fmt::format("M563 P{} D0\n", i % 6);
    return config + "M563 P7 D0\n";
  };
  SourceManager sm;
  MachineResult r = lint_one_rule(sm, config_with(256), "RRF301");
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].message.find("does not exist yet") != std::string::npos);
  REQUIRE(r.diagnostics[0].fix);
  CHECK(r.diagnostics[0].fix->title == "move the line after the 'M563 P7'");
  SourceManager sm2;
  r = lint_one_rule(sm2, config_with(257), "RRF301");
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].message.find("does not exist yet") != std::string::npos);
  CHECK_FALSE(r.diagnostics[0].fix);
}

namespace {

// The reference: walk a line from its start, a code point at a time (an invalid byte is one code point).
size_t walk_floor(std::string_view s, size_t off, uint32_t* before = nullptr, bool round_up = false) {
  size_t i = 0;
  uint32_t n = 0;
  while (i < off && i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    size_t len = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 1;
    if (i + len > s.size()) len = 1;
    for (size_t k = 1; k < len; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) len = 1;
    if (i + len > off && !round_up) break;
    i += len;
    ++n;
  }
  if (before) *before = n;
  return std::min(i, s.size());
}

}  // namespace

TEST_CASE("columns and character boundaries on long lines are found near the offset, as a walk from the start would",
          "[robustness]") {
  // position() and code_point_floor() walked each line from its start: a long line of many commands, a finding
  // each, cost the square of its length to render (a 260 KB line: 5 s for JSON, 14 s for SARIF).
  const char alphabet[] = {'a', ' ', '\x80', '\xBF', '\xC3', '\xE2', '\xF0', '\xF5', '\xC0', '\n'};
  uint32_t seed = 12345;
  auto next = [&] { return seed = seed * 1103515245u + 12345u; };
  for (int round = 0; round < 200; ++round) {
    std::string text;
    const size_t n = next() % 60;
    for (size_t k = 0; k < n; ++k) text += alphabet[(next() >> 8) % sizeof alphabet];
    SourceManager sm;
    const SourceFile& f = sm.add("c.g", "/sys/c.g", text);
    for (size_t off = 0; off <= text.size() + 1; ++off) CHECK(code_point_floor(text, off) == walk_floor(text, off));
    // Offsets in a random order, and in order: the per-thread memory of the last count must not leak into the
    // next one.
    std::vector<uint32_t> offsets;
    for (uint32_t off = 0; off <= text.size(); ++off) offsets.push_back(off);
    for (int pass = 0; pass < 2; ++pass) {
      for (uint32_t off : offsets)
        for (bool up : {false, true}) {
          const LineCol at = f.position(off, up);
          const Span line = f.line_span(at.line - 1);
          const std::string_view s = std::string_view(text).substr(line.begin, line.end - line.begin);
          uint32_t before = 0;
          walk_floor(s, std::min(off, line.end) - line.begin, &before, up);
          CHECK(at.column == before + 1 + (off > line.end ? 1 : 0));
        }
      for (size_t k = offsets.size(); k > 1; --k) std::swap(offsets[k - 1], offsets[next() % k]);
    }
  }
}
