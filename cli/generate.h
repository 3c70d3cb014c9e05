// What the build generates from the command line's own definition and the rule registry, so that neither can
// go stale: the man page (manpage.cc) and the bash completion (completion.cc). `rrflint rule --generate-man FILE`
// and `rrflint rule --generate-completion FILE` write them; CMakeLists.txt runs both and installs the results.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace rrflint {
class RuleSet;
}

namespace rrflint::cli {

/// One option as the generators see it: every spelling, its value's name and choices, its help.
struct OptionDoc {
  std::vector<std::string> names;    // "-o", "--output-file"; a positional: its name
  std::string value;                 // "FILE", "FORMAT" …; empty for a flag
  std::vector<std::string> choices;  // from CLI::IsMember, else empty
  std::string help;
  bool positional = false;
  bool repeats = false;  // a positional taking several values
};

/// The options of a command: CLI11's, then those its footer documents (parsed before CLI11 sees them).
std::vector<OptionDoc> option_docs(const CLI::App& command);

/// The man page rrflint.1 (roff, man macros) for `app` and its subcommands, with every rule of `rules`.
/// `docdir`: where the rule pages are installed, relative to the prefix (FILES).
std::string man_page(const CLI::App& app, const RuleSet& rules, std::string_view docdir);

/// A bash completion script for `app`: its subcommands, their options, the choices of each option, and rule codes
/// and names for the options that take rules.
std::string bash_completion(const CLI::App& app, const RuleSet& rules);

/// The folder the rule pages are installed in, relative to the prefix (docs_url.cc: CMAKE_INSTALL_DOCDIR/rules).
std::string installed_rule_docs();

}  // namespace rrflint::cli
