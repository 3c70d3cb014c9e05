// Helpers for tests that run the rrflint binary on scratch folders: a temporary tree, and a command runner
// that captures stdout, stderr and the exit code.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rrflint::test {

namespace fs = std::filesystem;

/// Under CI=true (.ci/run on the CI machine, where scripts/setup.sh --test has installed every tool a test needs).
inline bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

/// A part of a test that cannot run here (a tool, a file or a user missing): a warning on a developer's machine, a
/// failure under CI=true, where a skip would pass without testing. `msg` is a Catch2 message expression.
#define RRFLINT_SKIPPED(msg)                                      \
  do {                                                            \
    if (::rrflint::test::in_ci()) FAIL_CHECK("NOT RUN: " << msg); \
    else WARN("SKIPPED: " << msg);                                \
  } while (0)

/// A scratch folder, removed at the end of the test.
class TempTree {
 public:
  TempTree() {
    std::string tmpl = (fs::temp_directory_path() / "rrflint-test-XXXXXX").string();
    char* d = ::mkdtemp(tmpl.data());
    root_ = d ? fs::path(d) : fs::path(tmpl);
  }
  ~TempTree() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  TempTree(const TempTree&) = delete;
  TempTree& operator=(const TempTree&) = delete;

  const fs::path& root() const { return root_; }
  fs::path operator/(const std::string& rel) const { return root_ / rel; }
  /// Writes a file (creating folders), bytes as given.
  fs::path write(const std::string& rel, const std::string& text) const {
    fs::path p = root_ / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string read(const std::string& rel) const {
    std::ifstream in(root_ / rel, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

 private:
  fs::path root_;
};

struct Output {
  int code = -1;
  std::string out, err;
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs `rrflint <args>` in `cwd` (args are passed to the shell as written: quote paths with shell_quote).
/// `env` is prepended (e.g. "NO_COLOR=1"); GITHUB_ACTIONS and colour variables are cleared first so the
/// tests do not depend on where they run.
inline Output run_rrflint(const fs::path& cwd, const std::string& args, const std::string& env = "",
                          const std::string& stdin_text = "") {
  static int counter = 0;
  const fs::path base =
      fs::temp_directory_path() / ("rrflint-cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  const std::string out = base.string() + ".out", err = base.string() + ".err", in = base.string() + ".in";
  std::ofstream(in, std::ios::binary) << stdin_text;
  const std::string cmd = "cd " + shell_quote(cwd.string()) +
                          " && env -u GITHUB_ACTIONS -u FORCE_COLOR -u NO_COLOR -u CLICOLOR_FORCE TERM=xterm " + env +
                          " " + shell_quote(RRFLINT_BINARY) + " " + args + " < " + shell_quote(in) + " > " +
                          shell_quote(out) + " 2> " + shell_quote(err);
  const int status = std::system(cmd.c_str());
  Output o;
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto slurp = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  };
  o.out = slurp(out);
  o.err = slurp(err);
  std::error_code ec;
  fs::remove(out, ec);
  fs::remove(err, ec);
  fs::remove(in, ec);
  return o;
}

inline bool contains(const std::string& hay, const std::string& needle) {
  return hay.find(needle) != std::string::npos;
}

}  // namespace rrflint::test
