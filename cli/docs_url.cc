// Where the links rrflint prints point: the folder of the rule pages (docs/rules/<name>.md).
//
//   1. `docs-url` in .rrflint.toml (settings.cc), when set;
//   2. else the CMake option RRFLINT_DOCS_URL, when the build set it (packagers: their web or local copy);
//   3. else the docs this build installs, file://<CMAKE_INSTALL_FULL_DOCDIR>/rules/ — unless the binary runs from
//      its build tree (its own path is below CMAKE_BINARY_DIR, read from /proc/self/exe), or nothing is
//      installed there, and the source tree's docs/rules/ exists: then file://<source>/docs/rules/.
//
// The folders are compiled into this file only (CMakeLists.txt), so the rest of the build does not depend on
// where the source tree or the install prefix is.
#include <fmt/format.h>

#include <cctype>

#include "cli/cli.h"

#ifndef RRFLINT_DOCS_URL
#define RRFLINT_DOCS_URL ""
#endif
#ifndef RRFLINT_INSTALL_DOCDIR
#define RRFLINT_INSTALL_DOCDIR "/usr/local/share/doc/rrflint"
#endif
#ifndef RRFLINT_SOURCE_DIR
#define RRFLINT_SOURCE_DIR ""
#endif
#ifndef RRFLINT_BUILD_DIR
#define RRFLINT_BUILD_DIR ""
#endif

namespace rrflint::cli {

std::string file_url(const fs::path& dir) {
  std::string p = dir.lexically_normal().generic_string();
  if (!p.starts_with("/")) p = "/" + p;
  std::string out = "file://";
  for (unsigned char c : p) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') out += static_cast<char>(c);
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
  const fs::path installed = fs::path(RRFLINT_INSTALL_DOCDIR) / "rules";
  const std::string_view source_dir = RRFLINT_SOURCE_DIR, build_dir = RRFLINT_BUILD_DIR;
  if (!source_dir.empty()) {
    const fs::path source = fs::path(source_dir) / "docs" / "rules";
    bool from_build_tree = false;
    if (!build_dir.empty()) {
      const fs::path self = fs::read_symlink("/proc/self/exe", ec);
      from_build_tree = !ec && relative_below(self, fs::path(build_dir)).has_value();
    }
    if ((from_build_tree || !fs::is_directory(installed, ec)) && fs::is_directory(source, ec)) return file_url(source);
  }
  return file_url(installed);
}

}  // namespace rrflint::cli
