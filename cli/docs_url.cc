// Where the links rrflint prints point: the folder of the rule pages (docs/rules/<name>.md).
//
//   1. `docs-url` in .rrflint.toml (settings.cc), when set;
//   2. else the CMake option RRFLINT_DOCS_URL, when the build set it (packagers: their web or local copy);
//   3. else the docs this build installs: <bin>/../share/doc/rrflint/rules/ beside the running binary (so an
//      install moved to another prefix, a .deb, or the Windows zip's docs/rules/ are found), else
//      file://<CMAKE_INSTALL_FULL_DOCDIR>/rules/ — unless the binary runs from its build tree (its own path is
//      below CMAKE_BINARY_DIR), or nothing is installed there, and the source tree's docs/rules/ exists: then
//      file://<source>/docs/rules/.
//
// The folders are compiled into this file only (CMakeLists.txt), so the rest of the build does not depend on
// where the source tree or the install prefix is.
#include <fmt/format.h>

#include <cctype>

#ifdef _WIN32
#include "frontend/win32.h"
#endif

#include "cli/cli.h"

#ifndef RRFLINT_DOCS_URL
#define RRFLINT_DOCS_URL ""
#endif
#ifndef RRFLINT_INSTALL_DOCDIR
#define RRFLINT_INSTALL_DOCDIR "/usr/local/share/doc/rrflint"
#endif
#ifndef RRFLINT_DOCDIR_FROM_BINDIR
#define RRFLINT_DOCDIR_FROM_BINDIR "../share/doc/rrflint"
#endif
#ifndef RRFLINT_DOCDIR
#define RRFLINT_DOCDIR "share/doc/rrflint"
#endif
#ifndef RRFLINT_SOURCE_DIR
#define RRFLINT_SOURCE_DIR ""
#endif
#ifndef RRFLINT_BUILD_DIR
#define RRFLINT_BUILD_DIR ""
#endif

namespace rrflint::cli {

namespace {

// The running binary's own path; empty when it cannot be told.
fs::path self_path() {
  std::error_code ec;
#ifdef _WIN32
  std::wstring buf(32768, L'\0');
  const DWORD n = GetModuleFileNameW(nullptr, buf.data(), static_cast<DWORD>(buf.size()));
  if (n == 0 || n >= buf.size()) return {};
  buf.resize(n);
  return fs::path(buf);
#else
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : self;
#endif
}

}  // namespace

std::string installed_rule_docs() { return RRFLINT_DOCDIR "/rules"; }

std::string file_url(const fs::path& dir) {
  std::string p = dir.lexically_normal().generic_string();
  if (!p.starts_with("/")) p = "/" + p;
  // A Windows drive letter keeps its colon: file:///C:/rrflint/docs/rules/.
  const bool drive = p.size() >= 3 && std::isalpha(static_cast<unsigned char>(p[1])) && p[2] == ':';
  std::string out = "file://";
  for (size_t i = 0; i < p.size(); ++i) {
    const auto c = static_cast<unsigned char>(p[i]);
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/' || (drive && i == 2))
      out += static_cast<char>(c);
    else out += fmt::format("%{:02X}", c);
  }
  if (!out.ends_with('/')) out += '/';
  return out;
}

std::string default_docs_base() {
  if (const std::string_view packaged = RRFLINT_DOCS_URL; !packaged.empty()) {
    std::string why;
    if (auto url = parse_docs_url(packaged, &why)) return *url;
  }
  std::error_code ec;
  const fs::path self = self_path(), installed = fs::path(RRFLINT_INSTALL_DOCDIR) / "rules";
  const std::string_view source_dir = RRFLINT_SOURCE_DIR, build_dir = RRFLINT_BUILD_DIR;
  const fs::path source = source_dir.empty() ? fs::path() : fs::path(source_dir) / "docs" / "rules";
  const bool from_build_tree =
      !self.empty() && !build_dir.empty() && relative_below(self, fs::path(build_dir)).has_value();
  if (from_build_tree && !source.empty() && fs::is_directory(source, ec)) return file_url(source);
  if (!self.empty()) {
    const fs::path beside = self.parent_path() / RRFLINT_DOCDIR_FROM_BINDIR / "rules";
    if (fs::is_directory(beside, ec)) return file_url(beside);
  }
  if (!fs::is_directory(installed, ec) && !source.empty() && fs::is_directory(source, ec)) return file_url(source);
  return file_url(installed);
}

}  // namespace rrflint::cli
