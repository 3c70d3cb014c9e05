// The engine's choice of rules: which rules a run's options switch on (enabled_rules), and which node rules each
// command wakes (the dispatch table lint_machine keeps per thread while the rules stay the same).
#include <catch2/catch.hpp>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "lint/engine/linter.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

std::vector<std::string> codes(const std::vector<const Rule*>& rules) {
  std::vector<std::string> out;
  for (const Rule* r : rules) out.emplace_back(r->meta.code);
  return out;
}

LintOptions selecting(std::vector<std::string> select, std::vector<std::string> ignore = {}) {
  LintOptions o;
  o.select = std::move(select);
  o.ignore = std::move(ignore);
  return o;
}

}  // namespace

TEST_CASE("registry: codes RRF and three digits, names lower-case kebab, both unique", "[engine][select]") {
  // RuleSet::find and the suppression comments' "did you mean" compare a key with names as written: they rely on
  // every name being lower case.
  const std::regex code("RRF[0-9]{3}");
  const std::regex name("[a-z0-9]+(-[a-z0-9]+(\\.[0-9]+)*)*");
  std::set<std::string> codes_seen, names_seen;
  for (const Rule* r : builtin_rules().all()) {
    INFO(r->meta.code << " " << r->meta.name);
    CHECK(std::regex_match(std::string(r->meta.code), code));
    CHECK(std::regex_match(std::string(r->meta.name), name));
    CHECK(codes_seen.emplace(r->meta.code).second);
    CHECK(names_seen.emplace(r->meta.name).second);
  }
  CHECK(codes_seen.size() >= 50);
}

TEST_CASE("enabled rules: codes and names in any case, code prefixes, ALL, and what is not a rule",
          "[engine][select]") {
  const RuleSet& all = builtin_rules();
  std::vector<std::string> errors;
  CHECK(codes(enabled_rules(all, selecting({"rrf301"}), &errors)) == std::vector<std::string>{"RRF301"});
  CHECK(codes(enabled_rules(all, selecting({"G10-Tool-Before-Definition"}), &errors)) ==
        std::vector<std::string>{"RRF301"});
  CHECK(errors.empty());

  // A prefix selects a family, in code order; ignore takes rules back out, by prefix too.
  const auto family = codes(enabled_rules(all, selecting({"rrf32"}), &errors));
  REQUIRE(family.size() >= 5);
  CHECK(std::is_sorted(family.begin(), family.end()));
  for (const std::string& c : family) CHECK(c.starts_with("RRF32"));
  const auto fewer = codes(enabled_rules(all, selecting({"Rrf3"}, {"RRF32", "rrf301"}), &errors));
  for (const std::string& c : fewer) CHECK((c.starts_with("RRF3") && !c.starts_with("RRF32") && c != "RRF301"));
  CHECK(std::find(fewer.begin(), fewer.end(), "RRF302") != fewer.end());

  CHECK(enabled_rules(all, selecting({"All"}), &errors).size() == all.all().size());
  CHECK(enabled_rules(all, selecting({"ALL"}, {"all"}), &errors).empty());
  CHECK(errors.empty());

  // Not a rule, not a prefix of one (RRF9999 is longer than every code), too short to be a prefix: errors.
  CHECK(enabled_rules(all, selecting({"g10-nothing", "RRF9999", "RRF"}), &errors).empty());
  CHECK(errors == std::vector<std::string>{"g10-nothing", "RRF9999", "RRF"});

  // No select: the rules on by default.
  errors.clear();
  const auto defaults = enabled_rules(all, LintOptions{}, &errors);
  for (const Rule* r : defaults) CHECK(r->meta.default_enabled);
  size_t on = 0;
  for (const Rule* r : all.all()) on += r->meta.default_enabled;
  CHECK(defaults.size() == on);
}

namespace {

// A node rule that reports every command it is called for: what it reports is what the dispatch table gave it.
void report_every(const NodeContext& ctx, Sink& sink);

Rule probe_rule{RuleMeta{"RRF999", "test-probe", Severity::Warning, true, FixAvailability::None, RuleTag::None,
                         "reports every command it is called for", ""},
                nullptr, report_every};

void report_every(const NodeContext& ctx, Sink& sink) {
  if (ctx.is_command()) sink.report(probe_rule.meta, ctx.at(ctx.command().span), "called");
}

std::vector<uint32_t> lines_reported(std::string_view on) {
  probe_rule.on = on;
  const RuleSet rules({&probe_rule});
  MemoryReader reader;
  reader.add("/sys/config.g", "G10 P1 X0\nM563 P1 D0\nT1\nG10 P1 Y0\n");
  SourceManager sources;
  const MachineResult r = lint_machine(sources, reader, rules, LintOptions{});
  std::vector<uint32_t> lines;
  for (const Diagnostic& d : r.diagnostics) lines.push_back(sources.get(d.loc.file).position(d.loc.span.begin).line);
  return lines;
}

}  // namespace

TEST_CASE("node dispatch: each run's rules get the commands their `on` lists name", "[engine]") {
  // The same rule object, at the same address, with another `on` list each run: the table made for the first
  // run must not serve the next.
  CHECK(lines_reported("G10") == std::vector<uint32_t>{1, 4});
  CHECK(lines_reported("M563") == std::vector<uint32_t>{2});
  CHECK(lines_reported("M563") == std::vector<uint32_t>{2});
  CHECK(lines_reported("T G10") == std::vector<uint32_t>{1, 3, 4});
  CHECK(lines_reported("M584").empty());
}
