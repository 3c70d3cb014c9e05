// Google Benchmark programs for the core (issue 2 §8). Benchmarks, never timed tests.
//
//   BM_Parse/<size>      line index + parser on a generated file (bench/out/gen-<size>.g): MB/s
//   BM_LintFile/<size>   the whole pipeline on that file as /sys/config.g, default rules
//   BM_LintCorpusFolder  the whole pipeline on the median corpus folder (../shared/corpus), from disk
//   BM_Relint300         P5: an editor's re-lint of a 300-line config.g plus three macros, in memory
//
// bench/run.sh generates the inputs and runs this in a Release build. Inputs that are missing are skipped
// with a message, not failed.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "frontend/disk.h"
#include "lint/engine/linter.h"
#include "rules/registry.h"

namespace fs = std::filesystem;
using namespace rrflint;

namespace {

const fs::path kSource = RRFLINT_SOURCE_DIR;

std::string generated(const std::string& size) {
  std::string err;
  auto bytes = read_file(kSource / "bench" / "out" / ("gen-" + size + ".g"), &err);
  return bytes ? *bytes : std::string();
}

void parse_file(benchmark::State& state, const std::string& size) {
  const std::string text = generated(size);
  if (text.empty()) {
    state.SkipWithError(("bench/out/gen-" + size + ".g is missing: run bench/run.sh").c_str());
    return;
  }
  size_t commands = 0;
  for (auto _ : state) {
    SourceFile file(0, "gen.g", "/sys/config.g", text);
    ParsedFile pf = parse(file);
    commands = pf.commands.size();
    size_t lines = pf.lines.size();
    benchmark::DoNotOptimize(lines);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
  state.counters["commands"] = static_cast<double>(commands);
}

void lint_file(benchmark::State& state, const std::string& size) {
  const std::string text = generated(size);
  if (text.empty()) {
    state.SkipWithError(("bench/out/gen-" + size + ".g is missing: run bench/run.sh").c_str());
    return;
  }
  size_t findings = 0;
  for (auto _ : state) {
    SourceManager sources;
    MemoryReader reader;
    reader.add("/sys/config.g", text);
    MachineResult r = lint_machine(sources, reader, builtin_rules(), LintOptions{});
    findings = r.diagnostics.size();
    benchmark::DoNotOptimize(r.diagnostics.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
  state.counters["findings"] = static_cast<double>(findings);
}

void BM_Parse_1M(benchmark::State& s) { parse_file(s, "1M"); }
void BM_Parse_10M(benchmark::State& s) { parse_file(s, "10M"); }
void BM_LintFile_1M(benchmark::State& s) { lint_file(s, "1M"); }
void BM_LintFile_10M(benchmark::State& s) { lint_file(s, "10M"); }
BENCHMARK(BM_Parse_1M)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Parse_10M)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LintFile_1M)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LintFile_10M)->Unit(benchmark::kMillisecond);

/// The corpus folder whose total size is the median, so the number is typical rather than extreme.
std::optional<fs::path> median_corpus_folder() {
  const fs::path corpus = kSource / ".." / "shared" / "corpus";
  std::error_code ec;
  if (!fs::is_directory(corpus, ec)) return std::nullopt;
  std::vector<std::pair<uintmax_t, fs::path>> sized;
  for (const auto& d : fs::directory_iterator(corpus, ec)) {
    if (!d.is_directory()) continue;
    uintmax_t total = 0;
    for (const auto& f : fs::recursive_directory_iterator(d.path(), ec))
      if (f.is_regular_file()) total += f.file_size();
    sized.emplace_back(total, d.path());
  }
  if (sized.empty()) return std::nullopt;
  std::sort(sized.begin(), sized.end());
  return sized[sized.size() / 2].second;
}

void BM_LintCorpusFolder(benchmark::State& state) {
  static const std::optional<fs::path> folder = median_corpus_folder();
  if (!folder) {
    state.SkipWithError("../shared/corpus not found");
    return;
  }
  auto card = card_at(*folder);
  if (!card) {
    state.SkipWithError("the median corpus folder has no sys/config.g");
    return;
  }
  size_t files = 0;
  for (auto _ : state) {
    SourceManager sources;
    DiskReader reader(card->root, card->sys_dir, card->root);
    MachineResult r = lint_machine(sources, reader, builtin_rules(), LintOptions{});
    files = r.machine->unit_count();
    benchmark::DoNotOptimize(r.diagnostics.data());
  }
  state.SetLabel(folder->filename().string());
  state.counters["files"] = static_cast<double>(files);
}
BENCHMARK(BM_LintCorpusFolder)->Unit(benchmark::kMicrosecond);

/// A realistic 300-line config.g for a two-tool IDEX printer: header, network, drives, axes, endstops,
/// probe, heaters, fans, tools with offsets, a few meta commands, M501.
std::string config300() {
  std::vector<std::string> l = {
      "; Configuration file for Duet 3 MB 6HC (firmware version 3.5)",
      "; generated for the rrflint P5 benchmark",
      "G90                                   ; absolute coordinates",
      "M83                                   ; relative extruder moves",
      "M550 P\"Bench IDEX\"                    ; printer name",
      "M551 P\"secret\"",
      "M552 S1",
      "M586 P0 S1",
      "M586 P1 S0",
      "M575 P1 S1 B57600",
      "G4 S2                                 ; wait for expansion boards",
  };
  for (int d = 0; d < 7; ++d) l.push_back(fmt::format("M569 P0.{} S{} D2", d, d % 2));
  l.push_back("M584 X0.0 Y0.1 Z0.2:0.3 U0.4 E0.5:0.6  ; drive mapping");
  l.push_back("M350 X16 Y16 Z16 U16 E16:16 I1");
  l.push_back("M92 X80.00 Y80.00 Z400.00 U80.00 E420.00:420.00");
  l.push_back("M566 X900.00 Y900.00 Z60.00 U900.00 E120.00:120.00");
  l.push_back("M203 X12000.00 Y12000.00 Z900.00 U12000.00 E3600.00:3600.00");
  l.push_back("M201 X1500.00 Y1500.00 Z100.00 U1500.00 E2500.00:2500.00");
  l.push_back("M906 X1200 Y1200 Z1000 U1200 E700:700 I30");
  l.push_back("M84 S30");
  l.push_back("M208 X-20:300 Y0:300 Z0:350 U0:340");
  l.push_back("M574 X1 S1 P\"io0.in\"");
  l.push_back("M574 U2 S1 P\"io1.in\"");
  l.push_back("M574 Y1 S1 P\"!io2.in\"");
  l.push_back("M574 Z1 S2");
  l.push_back("M558 P8 C\"io3.in\" H5 F120 T6000");
  l.push_back("G31 P500 X0 Y25 Z1.85");
  l.push_back("M557 X15:285 Y15:285 S30");
  l.push_back("M671 X-40:340 Y150:150 S5");
  for (int h = 0; h < 3; ++h) {
    l.push_back(fmt::format("M308 S{} P\"temp{}\" Y\"thermistor\" T100000 B{} A\"Heater {}\"", h, h, 4138 + h, h));
    l.push_back(fmt::format("M950 H{} C\"out{}\" T{}", h, h, h));
    l.push_back(fmt::format("M307 H{} R2.43 K0.56:0.00 D5.5 E1.35 S1.00 B0 V24.0", h));
    l.push_back(fmt::format("M143 H{} S{}", h, h ? 285 : 120));
  }
  l.push_back("M140 H0");
  for (int f = 0; f < 4; ++f) {
    l.push_back(fmt::format("M950 F{} C\"out{}\" Q500", f, f + 4));
    l.push_back(fmt::format("M106 P{} S{} H{} T45", f, f % 2, f < 2 ? 1 + f : -1));
  }
  l.push_back("M563 P0 S\"Left\" D0 H1 F0");
  l.push_back("G10 P0 X0 Y0 Z0");
  l.push_back("G10 P0 R0 S0");
  l.push_back("M563 P1 S\"Right\" D1 H2 X3 F2");
  l.push_back("G10 P1 U0 Y0 Z0");
  l.push_back("M568 P1 R0 S0");
  l.push_back("M563 P2 S\"Copy\" D0:1 H1:2 X0:3 F0:2");
  l.push_back("G10 P2 X-50 Y0 U50 Z0");
  l.push_back("M567 P2 E1:1");
  l.push_back("if !exists(global.parkU)");
  l.push_back("  global parkU = 340");
  l.push_back("if !exists(global.purge)");
  l.push_back("  global purge = 12.5");
  l.push_back("M98 P\"speeds.g\"");
  l.push_back("M98 P\"0:/macros/leds.g\" S1");
  l.push_back("M911 S21.0 R23.0 P\"M913 X0 Y0 G91 M83 G1 Z3 E-5 F1000\"");
  l.push_back("M501");
  l.push_back("T0 P0");
  // Fill to 300 lines with commented settings and a few moves, the way real configs grow.
  for (int i = 0; l.size() < 299; ++i) {
    switch (i % 6) {
      case 0: l.push_back(fmt::format("; --- section {} ---", i / 6)); break;
      case 1: l.push_back(fmt::format("M204 P{} T{}", 500 + i, 1000 + i)); break;
      case 2: l.push_back(fmt::format("M566 X{}.00 Y{}.00", 800 + i, 800 + i)); break;
      case 3: l.push_back(fmt::format(";M572 D0 S0.0{}     ; pressure advance, tuned later", i % 10)); break;
      case 4: l.push_back(fmt::format("M207 S{}.{} F3600 Z0.2", 1 + i % 3, i % 10)); break;
      default: l.push_back(fmt::format("echo \"config line {}\"", i)); break;
    }
  }
  l.push_back("M929 P\"eventlog.txt\" S1");
  std::string out;
  for (const std::string& s : l) out += s + "\n";
  return out;
}

void BM_Relint300(benchmark::State& state) {
  const std::string config = config300();
  const std::string speeds = "M203 X15000 Y15000\nM201 X2000 Y2000\n";
  const std::string leds = "if param.S == 1\n  M150 R255 U255 B255 P128\nelse\n  M150 P0\n";
  const std::string tpost = "M116 P0\nM568 P0 A2\n";
  size_t findings = 0;
  for (auto _ : state) {
    SourceManager sources;
    MemoryReader reader;
    reader.add("/sys/config.g", config);
    reader.add("/sys/speeds.g", speeds);
    reader.add("/macros/leds.g", leds);
    reader.add("/sys/tpost0.g", tpost);
    MachineResult r = lint_machine(sources, reader, builtin_rules(), LintOptions{});
    findings = r.diagnostics.size();
    benchmark::DoNotOptimize(r.diagnostics.data());
  }
  state.counters["lines"] = 300;
  state.counters["findings"] = static_cast<double>(findings);
}
BENCHMARK(BM_Relint300)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
