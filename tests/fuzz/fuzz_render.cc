// libFuzzer target: the renderers, on the findings of a card in the card format of tests/fuzz/fuzz_input.h. The
// JSON, JSON Lines, SARIF and GitLab reports (and the model as JSON) must parse back with nlohmann-json and have their
// expected structure, with one entry per finding; the text, concise and GitHub renderers must run. Run it with
// scripts/fuzz.sh (tests/fuzz/RESULTS.md).
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <set>
#include <sstream>
#include <string>
#include <string_view>

#include "lint/render/model_render.h"
#include "tests/fuzz/fuzz_input.h"

using namespace rrflint;
using nlohmann::json;

namespace {

json parsed(const std::string& text) {
  json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) __builtin_trap();
  return j;
}

bool is_array_of(const json& j, const char* key, size_t n) {
  return j.is_object() && j.contains(key) && j[key].is_array() && j[key].size() == n;
}

void check_diagnostic(const json& d) {
  for (const char* k : {"code", "name", "severity", "message", "file", "url"})
    if (!d.contains(k) || !d[k].is_string()) __builtin_trap();
  for (const char* k : {"line", "column", "end_line", "end_column"})
    if (!d.contains(k) || !d[k].is_number_unsigned()) __builtin_trap();
  if (!d.contains("notes") || !d["notes"].is_array() || !d.contains("fix")) __builtin_trap();
}

void check_json(const SourceManager& sm, const MachineResult& r, const RenderOptions& ro) {
  std::ostringstream os;
  render_json(os, sm, r.diagnostics, ro);
  const json doc = parsed(os.str());
  if (doc.value("version", 0) != 1 || !is_array_of(doc, "diagnostics", r.diagnostics.size()) ||
      !is_array_of(doc, "machines", 1) || !doc.contains("summary") || !doc["summary"].is_object())
    __builtin_trap();
  for (const json& d : doc["diagnostics"]) check_diagnostic(d);
  // A fix's edits carry their text as written (line endings included), only invalid UTF-8 replaced.
  for (size_t i = 0; i < r.diagnostics.size(); ++i) {
    const Diagnostic& d = r.diagnostics[i];
    const json& f = doc["diagnostics"][i]["fix"];
    if (!d.fix) {
      if (!f.is_null()) __builtin_trap();
      continue;
    }
    if (!is_array_of(f, "edits", d.fix->edits.size())) __builtin_trap();
    for (size_t k = 0; k < d.fix->edits.size(); ++k)
      if (f["edits"][k].value("replacement", std::string("\x01")) != valid_utf8(d.fix->edits[k].replacement))
        __builtin_trap();
  }

  std::ostringstream lines;
  render_json_lines(lines, sm, r.diagnostics, ro);
  std::istringstream in(lines.str());
  size_t n = 0;
  for (std::string line; std::getline(in, line); ++n) check_diagnostic(parsed(line));
  if (n != r.diagnostics.size()) __builtin_trap();
}

void check_sarif(const SourceManager& sm, const MachineResult& r, const RenderOptions& ro) {
  std::ostringstream os;
  render_sarif(os, sm, r.diagnostics, ro);
  const json doc = parsed(os.str());
  if (doc.value("version", "") != "2.1.0" || !doc.contains("$schema") || !is_array_of(doc, "runs", 1)) __builtin_trap();
  const json& run = doc["runs"][0];
  if (!is_array_of(run, "results", r.diagnostics.size()) || !run.contains("tool")) __builtin_trap();
  const json& driver = run["tool"].value("driver", json());
  if (driver.value("name", "") != "rrflint" || !is_array_of(driver, "rules", ro.rules ? ro.rules->all().size() : 0))
    __builtin_trap();
  for (const json& res : run["results"])
    if (!res.contains("ruleId") || !res.contains("level") || !is_array_of(res, "locations", 1)) __builtin_trap();
}

// GitLab Code Quality: an array with one entry per finding, in order, and no fingerprint twice.
void check_gitlab(const SourceManager& sm, const MachineResult& r, const RenderOptions& ro) {
  std::ostringstream os;
  render_gitlab(os, sm, r.diagnostics, ro);
  const json doc = parsed(os.str());
  if (!doc.is_array() || doc.size() != r.diagnostics.size()) __builtin_trap();
  std::set<std::string> fingerprints;
  for (size_t i = 0; i < doc.size(); ++i) {
    const json& e = doc[i];
    if (e.value("check_name", "") != r.diagnostics[i].code || !e.contains("description") ||
        !e["location"].contains("path") || !e["location"]["positions"]["begin"]["line"].is_number_unsigned() ||
        !fingerprints.insert(e.value("fingerprint", "")).second)
      __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const fuzz::LintedCard card(data, size);
  const SourceManager& sm = card.sources;
  const MachineResult& r = card.result;

  RenderOptions ro;
  // The rule list (every rule's docs, the bulk of a SARIF report) does not depend on the input: one input in 64
  // renders it, the others are spared the time.
  ro.rules = (data[0] & 0x3f) == 0 ? &builtin_rules() : nullptr;
  ro.docs_base = "https://example.org/rules/";
  ro.files_checked = sm.size();
  ro.machines.push_back({"card", r.target});
  check_json(sm, r, ro);
  check_sarif(sm, r, ro);
  check_gitlab(sm, r, ro);
  std::ostringstream model;
  render_model_json(model, sm, r, "card");
  if (!parsed(model.str()).is_object()) __builtin_trap();

  std::ostringstream sink;
  render_text(sink, sm, r.diagnostics, ro);
  render_concise(sink, sm, r.diagnostics, ro);
  render_github(sink, sm, r.diagnostics, ro);
  render_model_text(sink, sm, r, "card");
  return 0;
}
