// The man page, rrflint.1, from the CLI11 definition of the commands and the rule registry (see generate.h).
// roff with the man macros; text is escaped (backslashes, a leading '.' or '\'', minus signs in names) and every
// non-ASCII character is written as \[uXXXX], so groff needs no input encoding.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <sstream>

#include "cli/generate.h"
#include "lint/engine/rule.h"

namespace rrflint::cli {
namespace {

// Decodes one UTF-8 sequence at s[i] (advancing i); an invalid byte is U+FFFD.
char32_t next_code_point(std::string_view s, size_t& i) {
  const auto b = static_cast<unsigned char>(s[i++]);
  const int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : 0;
  if (b >= 0x80 && (extra == 0 || i + extra > s.size())) return 0xFFFD;
  char32_t c = extra == 0 ? b : b & (0x3F >> extra);
  for (int k = 0; k < extra; ++k) c = (c << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  return c;
}

// Text for roff. `name`: a command, option or rule name, whose '-' are minus signs (\-), so they copy and search
// as typed. Markdown `code` becomes bold.
std::string esc(std::string_view s, bool name = false) {
  std::string out;
  bool bold = false;
  for (size_t i = 0; i < s.size();) {
    const char c = s[i];
    if (c == '\\') out += "\\e", ++i;
    else if (c == '-' && (name || bold)) out += "\\-", ++i;
    else if (c == '`' && !name) out += (bold = !bold) ? "\\fB" : "\\fR", ++i;
    else if (static_cast<unsigned char>(c) >= 0x80) out += fmt::format("\\[u{:04X}]", uint32_t(next_code_point(s, i)));
    else out += c, ++i;
  }
  if (bold) out += "\\fR";
  if (out.starts_with('.') || out.starts_with('\'')) out.insert(0, "\\&");
  return out;
}

// "\fB\-o\fR, \fB\-\-output\-file\fR \fIFILE\fR"
std::string option_head(const OptionDoc& o) {
  if (o.positional) return fmt::format("\\fI{}\\fR{}", esc(o.value), o.repeats ? " .\\|.\\|." : "");
  std::string head;
  for (const std::string& n : o.names) head += fmt::format("{}\\fB{}\\fR", head.empty() ? "" : ", ", esc(n, true));
  if (o.value.starts_with("[=")) head += fmt::format("[=\\fI{}\\fR]", esc(o.value.substr(2, o.value.size() - 3)));
  else if (!o.value.empty()) head += fmt::format(" \\fI{}\\fR", esc(o.value));
  return head;
}

void synopsis(std::ostream& out, const CLI::App& app) {
  out << ".SH SYNOPSIS\n";
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    out << ".B rrflint " << esc(sub->get_name(), true) << "\n";
    std::string args = "[\\fIoptions\\fR]";
    for (const OptionDoc& o : option_docs(*sub)) {
      if (!o.positional) continue;
      const bool required = sub->get_option(o.names[0])->get_required();
      args += required ? " " + option_head(o) : " [" + option_head(o) + "]";
    }
    out << args << "\n.br\n";
  }
  out << ".B rrflint\n[\\fB\\-\\-help\\fR | \\fB\\-\\-version\\fR]\n";
}

void commands_and_options(std::ostream& out, const CLI::App& app) {
  const auto subs = app.get_subcommands([](const CLI::App*) { return true; });
  out << ".SH COMMANDS\n";
  for (const CLI::App* sub : subs)
    out << ".TP\n.B " << esc(sub->get_name(), true) << "\n" << esc(sub->get_description()) << ".\n";
  out << ".SH OPTIONS\nEvery command takes \\fB\\-h\\fR, \\fB\\-\\-help\\fR. Options that take a list of rules "
         "accept codes (RRF301), names (g10\\-tool\\-before\\-definition), code prefixes (RRF3) and ALL, "
         "separated by commas.\n";
  for (const CLI::App* sub : subs) {
    std::vector<OptionDoc> docs = option_docs(*sub);
    std::erase_if(docs, [](const OptionDoc& o) { return std::count(o.names.begin(), o.names.end(), "--help") > 0; });
    std::stable_partition(docs.begin(), docs.end(), [](const OptionDoc& o) { return o.positional; });
    if (docs.empty()) continue;
    out << ".SS \"rrflint " << esc(sub->get_name(), true) << "\"\n";
    for (const OptionDoc& o : docs) {
      const bool ends = !o.help.empty() && std::string_view(".)").find(o.help.back()) != std::string_view::npos;
      out << ".TP\n" << option_head(o) << "\n" << esc(o.help) << (ends ? "" : ".") << "\n";
    }
  }
}

void rules_section(std::ostream& out, const RuleSet& rules) {
  out << ".SH RULES\n"
         "Each rule has a code, a name, a default severity, and is on or off by default; "
         "\\fBrrflint rule\\fR \\fICODE\\fR prints its page.\n";
  for (const Rule* r : rules.all()) {
    const RuleMeta& m = r->meta;
    std::string fix = m.fix == FixAvailability::Always      ? ", fix"
                      : m.fix == FixAvailability::Sometimes ? ", fix sometimes"
                                                            : "";
    out << fmt::format(".TP\n\\fB{}\\fR \\fB{}\\fR ({}{}{})\n{}\n", m.code, esc(m.name, true),
                       severity_name(m.severity), m.default_enabled ? "" : ", off by default", fix, esc(m.summary));
  }
}

void tail_sections(std::ostream& out, std::string_view docdir) {
  out << R"(.SH EXIT STATUS
.TP
.B 0
Every file was linted and no finding reaches \fB\-\-fail\-on\fR (or \fB\-\-exit\-zero\fR was given).
.TP
.B 1
Every file was linted and at least one finding reaches \fB\-\-fail\-on\fR; \fB\-\-diff\fR with fixes to show.
.TP
.B 2
A usage error, or something could not be linted: a missing path, no file linted at all, a \fIconfig.g\fR that
cannot be read, a fix that could not be written.
.SH ENVIRONMENT
.TP
.B NO_COLOR
Not empty: no colour (text format).
.TP
.B FORCE_COLOR
Not empty and not 0: colour even when the output is not a terminal.
.TP
.B TERM
\fBdumb\fR: no colour.
.TP
.B GITHUB_ACTIONS
\fBtrue\fR: the default format is \fBgithub\fR (workflow commands).
.SH FILES
.TP
.I .rrflint.toml
Settings, found from each linted file's folder upward, up to the repository root (see \fBrrflint config\fR).
.TP
)"
      << "\\fIPREFIX\\fR/" << esc(docdir) << "/\n"
      << R"(The rule pages the printed links point at, one Markdown file per rule name. \fIPREFIX\fR is the folder
above the one that holds \fBrrflint\fR: \fI/usr\fR for the Debian package, \fI/usr/local\fR by default from source.
.SH EXAMPLES
.TP
.B rrflint check .
Lint every SD card (a folder whose \fIsys/\fR holds \fIconfig.g\fR) below the current folder.
.TP
.B rrflint check \-\-fix \-\-unsafe\-fixes sd/
Apply every fix, then report what is left.
.TP
.B rrflint check \-\-stdin\-filename sys/config.g \-
Lint standard input as the \fIconfig.g\fR of the card it names.
.SH SEE ALSO
The README of the rrflint sources; \fBrrflint rule \-\-all\fR for every rule page.
)";
}

}  // namespace

std::vector<OptionDoc> option_docs(const CLI::App& command) {
  std::vector<OptionDoc> docs;
  for (const CLI::Option* opt : command.get_options()) {
    OptionDoc d;
    d.positional = opt->get_positional();
    if (d.positional) d.names.push_back(opt->get_name(true));
    for (const std::string& s : opt->get_snames()) d.names.push_back("-" + s);
    for (const std::string& l : opt->get_lnames()) d.names.push_back("--" + l);
    const std::string type = opt->get_type_name();
    if (opt->get_type_size_max() > 0) d.value = type.substr(0, type.find(':'));
    if (const size_t open = type.find(":{"); open != std::string::npos) {
      std::stringstream list(type.substr(open + 2, type.find('}', open) - open - 2));
      for (std::string item; std::getline(list, item, ',');) d.choices.push_back(item);
    }
    d.help = opt->get_description();
    d.repeats = d.positional && opt->get_items_expected_max() > 1;
    docs.push_back(std::move(d));
  }
  // Footer lines "  --name[=VALUE]  help": options parsed before CLI11 sees the arguments.
  std::stringstream footer(command.get_footer());
  for (std::string line; std::getline(footer, line);) {
    const size_t start = line.find("--"), gap = line.find("  ", start);
    if (start == std::string::npos || gap == std::string::npos || line.find_first_not_of(' ') != start) continue;
    const std::string spec = line.substr(start, gap - start);
    const size_t bracket = spec.find('[');
    docs.push_back({{spec.substr(0, bracket)},
                    bracket == std::string::npos ? "" : spec.substr(bracket),
                    {},
                    line.substr(line.find_first_not_of(' ', gap))});
  }
  return docs;
}

std::string man_page(const CLI::App& app, const RuleSet& rules, std::string_view docdir) {
  std::ostringstream out;
  out << ".\\\" Generated by `rrflint rule --generate-man` from the command line and the rule registry.\n"
      << ".TH RRFLINT 1 \"\" \"rrflint " << RRFLINT_VERSION << "\" \"User Commands\"\n"
      << ".SH NAME\nrrflint \\- " << esc(app.get_description().substr(app.get_description().find(": ") + 2)) << "\n";
  synopsis(out, app);
  out << R"(.SH DESCRIPTION
\fBrrflint\fR reads the configuration of a RepRapFirmware (Duet) printer, \fIsys/config.g\fR and every macro
it runs, orders the commands the way the firmware runs them at boot, builds the machine they describe (axes,
drivers, heaters, sensors, fans, probes, tools), and reports the mistakes the firmware would silently ignore
or only show on a live board: an axis used before \fBM584\fR creates it, a tool offset on an axis the tool does
not use, a heater configured before \fBM950\fR creates it.
.PP
A \fIPATH\fR is an SD\-card root (a folder holding \fIsys/config.g\fR), a \fIsys\fR folder, a folder holding
several cards, single files (linted as part of the card around them), or \fB\-\fR for standard input.
Findings have a severity (error, warning, info), a rule code and name, and often a fix that \fB\-\-fix\fR applies.
)";
  commands_and_options(out, app);
  rules_section(out, rules);
  tail_sections(out, docdir);
  return out.str();
}

}  // namespace rrflint::cli
