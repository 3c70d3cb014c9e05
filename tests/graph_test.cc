// The command graph (docs/firmware-behaviour.md#m98-and-macros, #system-files): M98 resolution, M505, M501,
// runonce.g, tool macros, nesting limits, cycles, maybe flags and entries. A segment is rendered as one line of tokens:
//
//   >/sys/a.g(M98)   a file starts, and why it runs      <   the file ends
//   M98              a command (its word)                 =T0 / =T-1 / =T?   the moment a T selects a tool
//   a leading ? marks a node that only maybe runs (inside if/while, or called from there)
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "lint/boot/graph.h"
#include "lint/engine/linter.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

struct Built {
  SourceManager sources;
  MemoryReader reader;
  std::unique_ptr<Machine> machine;
  Graph graph;
};

std::unique_ptr<Built> build(const std::map<std::string, std::string>& files, Version fw = kLatestVersion,
                             size_t max_nodes = GraphOptions{}.max_nodes) {
  auto b = std::make_unique<Built>();
  for (const auto& [path, text] : files) b->reader.add(path, text);
  b->machine = std::make_unique<Machine>(b->sources, b->reader);
  GraphOptions o;
  o.firmware = fw;
  o.max_nodes = max_nodes;
  b->graph = build_graph(*b->machine, o);
  return b;
}

std::string token(const Built& b, const Node& n) {
  std::string out = n.maybe ? "?" : "";
  const FileUnit& u = b.machine->unit(n.unit);
  switch (n.kind) {
    case NodeKind::Enter: return out + ">" + u.sd_path + "(" + std::string(call_kind_name(n.call)) + ")";
    case NodeKind::Leave: return out + "<";
    case NodeKind::Command: return out + std::string(u.parsed.text(u.parsed.commands[n.index].word));
    case NodeKind::ToolSelect: {
      if (n.index != UINT32_MAX) return out + "=T" + std::to_string(n.index);
      const Command& c = u.parsed.commands[b.graph.nodes[n.call_site].index];
      return out + (c.has_number && c.number < 0 ? "=T-1" : "=T?");
    }
  }
  return "!";
}

std::string trace(const Built& b, const Segment& s) {
  std::string out;
  for (NodeId id = s.begin; id < s.end; ++id) out += (out.empty() ? "" : " ") + token(b, b.graph.nodes[id]);
  return out;
}

std::string boot(const Built& b) {
  for (const Segment& s : b.graph.segments)
    if (s.boot) return trace(b, s);
  return "(no boot)";
}

std::vector<std::string> entries(const Built& b) {
  std::vector<std::string> out;
  for (const Segment& s : b.graph.segments)
    if (!s.boot) out.push_back(trace(b, s));
  return out;
}

std::vector<std::string> events(const Built& b) {
  std::vector<std::string> out;
  for (const GraphEvent& e : b.graph.events) {
    std::string kind;
    switch (e.kind) {
      case GraphEvent::Kind::MissingFile: kind = "missing"; break;
      case GraphEvent::Kind::Cycle: kind = "cycle"; break;
      case GraphEvent::Kind::TooDeep: kind = "too-deep(" + std::to_string(e.limit) + ")"; break;
      case GraphEvent::Kind::OutsideRoot: kind = "outside-root"; break;
      case GraphEvent::Kind::OtherVolume: kind = "other-volume"; break;
      case GraphEvent::Kind::UnreadableFile: kind = "unreadable"; break;
    }
    const Node& n = b.graph.nodes[e.node];
    out.push_back(kind + " " + e.path + " at " + b.machine->unit(n.unit).sd_path + ":" + std::to_string(n.index));
  }
  return out;
}

}  // namespace

TEST_CASE("graph: M98 paths are relative to /sys unless absolute", "[graph]") {
  auto b = build({
      {"/sys/config.g",
       "M98 P\"a.g\"\nM98 P\"0:/macros/m.g\"\nM98 P\"/sys/sub/b.g\"\nM98 P\"../macros/m.g\"\nM98 P\"A.G\"\n"
       "M98 Psub/b.g\n"},
      {"/sys/a.g", "G1 X1\n"},
      {"/sys/sub/b.g", "G1 X2\n"},
      {"/macros/m.g", "G1 X3\n"},
  });
  CHECK(boot(*b) ==
        ">/sys/config.g(boot) M98 >/sys/a.g(M98) G1 < M98 >/macros/m.g(M98) G1 < M98 >/sys/sub/b.g(M98) G1 < "
        "M98 >/macros/m.g(M98) G1 < M98 >/sys/a.g(M98) G1 < M98 >/sys/sub/b.g(M98) G1 < <");
  CHECK(events(*b).empty());
  CHECK(entries(*b).empty());  // every file ran at boot
}

TEST_CASE("graph: missing files, other volumes and paths above the root are events", "[graph]") {
  auto b = build({
      {"/sys/config.g", "M98 P\"nothere.g\"\nM98 P\"../../up.g\"\nM98 P\"1:/sys/x.g\"\nM98 P{var.f}\nM83\n"},
  });
  CHECK(boot(*b) == ">/sys/config.g(boot) M98 M98 M98 M98 M83 <");
  CHECK(events(*b) == std::vector<std::string>{"missing /sys/nothere.g at /sys/config.g:0",
                                               "outside-root ../../up.g at /sys/config.g:1",
                                               "other-volume 1:/sys/x.g at /sys/config.g:2"});
}

TEST_CASE("graph: M505 changes the folder for later relative names", "[graph]") {
  auto b = build({
      {"/sys/config.g",
       "M98 P\"a.g\"\nM505 P\"alt\"\nM98 P\"a.g\"\nM501\nif move.axes[0].homed\n  M505 P\"/sys\"\nM98 P\"a.g\"\n"},
      {"/sys/a.g", "M83\n"},
      {"/sys/alt/a.g", "M82\n"},
      {"/sys/alt/config-override.g", "G10 P0 X1\n"},
  });
  CHECK(boot(*b) ==
        ">/sys/config.g(boot) M98 >/sys/a.g(M98) M83 < M505 M98 >/sys/alt/a.g(M98) M82 < "
        "M501 >/sys/alt/config-override.g(M501) G10 < ?M505 M98 >/sys/alt/a.g(M98) M82 < <");
  // A branch known at boot to run runs for certain: its M505 moves the folder.
  auto t = build({{"/sys/config.g", "M505 P\"alt\"\nif true\n  M505 P\"/sys\"\nM98 P\"a.g\"\n"},
                  {"/sys/a.g", "M83\n"},
                  {"/sys/alt/a.g", "M82\n"}});
  CHECK(boot(*t) == ">/sys/config.g(boot) M505 M505 M98 >/sys/a.g(M98) M83 < <");
}

TEST_CASE("graph: an M505 whose folder would not fit RRF's 120-character path keeps the old folder", "[graph]") {
  // "0:/sys/" + 22 x "abcd/" = 117 characters fits; the 23rd would make 122 (Platform::SetSysDir fails).
  std::string config;
  for (int i = 0; i < 30; ++i) config += "M505 P\"abcd\"\n";
  config += "M98 P\"a.g\"\n";
  std::string deep = "/sys";
  for (int i = 0; i < 22; ++i) deep += "/abcd";
  auto b = build({{"/sys/config.g", config}, {deep + "/a.g", "M83\n"}});
  CHECK(boot(*b).ends_with("M98 >" + deep + "/a.g(M98) M83 < <"));
}

TEST_CASE("graph: cycles are reported and not followed", "[graph]") {
  auto b = build({
      {"/sys/config.g", "M98 P\"a.g\"\n"},
      {"/sys/a.g", "M98 P\"b.g\"\n"},
      {"/sys/b.g", "M98 P\"a.g\"\nM98 P\"b.g\"\nM83\n"},
  });
  CHECK(boot(*b) == ">/sys/config.g(boot) M98 >/sys/a.g(M98) M98 >/sys/b.g(M98) M98 M98 M83 < < <");
  CHECK(events(*b) == std::vector<std::string>{"cycle /sys/a.g at /sys/b.g:0", "cycle /sys/b.g at /sys/b.g:1"});
}

TEST_CASE("graph: the nesting limit depends on the version", "[graph]") {
  // config.g uses one level: 10 levels from 3.4, 7 for 3.01-3.3.
  std::map<std::string, std::string> files{{"/sys/config.g", "M98 P\"n1.g\"\n"}};
  for (int i = 1; i < 12; ++i)
    files["/sys/n" + std::to_string(i) + ".g"] = "M98 P\"n" + std::to_string(i + 1) + ".g\"\n";
  files["/sys/n12.g"] = "M83\n";
  auto deepest = [](const Built& b) {
    int d = 0;
    for (const Node& n : b.graph.nodes) d = std::max<int>(d, n.depth);
    return d;
  };
  auto v34 = build(files, Version(3, 4, 0));
  CHECK(deepest(*v34) == 10);
  CHECK(events(*v34) == std::vector<std::string>{"too-deep(10) /sys/n10.g at /sys/n9.g:0"});
  auto v33 = build(files, Version(3, 3, 0));
  CHECK(deepest(*v33) == 7);
  CHECK(events(*v33) == std::vector<std::string>{"too-deep(7) /sys/n7.g at /sys/n6.g:0"});
  auto v31 = build(files, Version(3, 1, 1));
  CHECK(deepest(*v31) == 7);
}

TEST_CASE("graph: config-override.g runs at the M501, runonce.g after config.g", "[graph]") {
  auto b = build({
      {"/sys/config.g", "M563 P0 S\"T\"\nM501\nG10 P0 X1\n"},
      {"/sys/config-override.g", "G10 P0 X5\n"},
      {"/sys/runonce.g", "M500\n"},
  });
  CHECK(boot(*b) ==
        ">/sys/config.g(boot) M563 M501 >/sys/config-override.g(M501) G10 < G10 < >/sys/runonce.g(runonce) M500 <");
  // Without M501, config-override.g is an entry of its own.
  auto n = build({{"/sys/config.g", "M83\n"}, {"/sys/config-override.g", "G10 P0 X5\n"}});
  CHECK(entries(*n) == std::vector<std::string>{">/sys/config-override.g(entry) G10 <"});
  // The M501 node is the call site of the override file.
  const Node& enter = b->graph.nodes[3];
  REQUIRE(enter.kind == NodeKind::Enter);
  CHECK(enter.call == CallKind::M501);
  CHECK(b->graph.nodes[enter.call_site].index == 1);
}

TEST_CASE("graph: T runs tfree, tpre, tpost unless P says otherwise", "[graph]") {
  std::map<std::string, std::string> files{
      {"/sys/config.g", "T0\nT1\nT1\nT-1\nT1 P0\nT0 P2\nT\nT{global.t}\n"},
      {"/sys/tfree0.g", "M83\n"},
      {"/sys/tpre0.g", "M83\n"},
      {"/sys/tpost0.g", "M83\n"},
      {"/sys/tfree1.g", "M83\n"},
      {"/sys/tpre1.g", "M83\n"},
      {"/sys/tpost1.g", "M83\n"},
  };
  auto b = build(files);
  CHECK(boot(*b) ==
        ">/sys/config.g(boot) "
        "T0 >/sys/tpre0.g(tpre) M83 < =T0 >/sys/tpost0.g(tpost) M83 < "
        "T1 >/sys/tfree0.g(tfree) M83 < >/sys/tpre1.g(tpre) M83 < =T1 >/sys/tpost1.g(tpost) M83 < "
        "T1 "
        "T-1 >/sys/tfree1.g(tfree) M83 < =T-1 "
        "T1 =T1 "
        "T0 >/sys/tpre0.g(tpre) M83 < =T0 "
        "T "
        "T{global.t} ?=T? <");
}

TEST_CASE("graph: what follows M98, G28, G29 (no S) or G32 on its line never runs, what follows a T does", "[graph]") {
  // RRF hands the line buffer to the macro: the rest of the line is dropped (RRF111 reports it). Not modelled, the
  // M106 would have raised fan-before-creation, and an M584 would have created axes that never exist.
  auto b = build({
      {"/sys/config.g",
       "M98 P\"a.g\" M584 X0 M98 P\"a.g\"\nG28 M106 P0 S0\nG29 M83\nG29 S1 M83\nG32 M82\nG28.1 M84\nT-1 M116\n"
       "M98 P\"a.g\"\n"},
      {"/sys/a.g", "G4 S0\n"},
  });
  CHECK(
      boot(*b) ==
      ">/sys/config.g(boot) M98 >/sys/a.g(M98) G4 < G28 G29 G29 M83 G32 G28.1 M84 T-1 M116 M98 >/sys/a.g(M98) G4 < <");
}

TEST_CASE("graph: generic tpre.g/tpost.g/tfree.g only from 3.5", "[graph]") {
  std::map<std::string, std::string> files{
      {"/sys/config.g", "T0\nT1\n"}, {"/sys/tpre.g", "M83\n"}, {"/sys/tfree.g", "M82\n"}, {"/sys/tpost1.g", "M84\n"}};
  auto v35 = build(files, Version(3, 5, 0));
  CHECK(boot(*v35) ==
        ">/sys/config.g(boot) T0 >/sys/tpre.g(tpre) M83 < =T0 "
        "T1 >/sys/tfree.g(tfree) M82 < >/sys/tpre.g(tpre) M83 < =T1 >/sys/tpost1.g(tpost) M84 < <");
  auto v34 = build(files, Version(3, 4, 6));
  CHECK(boot(*v34) == ">/sys/config.g(boot) T0 =T0 T1 =T1 >/sys/tpost1.g(tpost) M84 < <");
  // The generic files are not reached at boot on 3.4, so they are entries there.
  CHECK(entries(*v34) == std::vector<std::string>{">/sys/tfree.g(entry) M82 <", ">/sys/tpre.g(entry) M83 <"});
}

TEST_CASE("graph: nodes inside if/while are maybe, and so is everything a maybe call runs", "[graph]") {
  auto b = build({
      {"/sys/config.g", "M83\nif exists(global.x)\n  M98 P\"a.g\"\nelse\n  T0\nwhile iterations < 2\n  M82\nM84\n"},
      {"/sys/a.g", "M98 P\"b.g\"\n"},
      {"/sys/b.g", "G1 X1\n"},
      {"/sys/tpre0.g", "G1 X2\n"},
  });
  CHECK(boot(*b) ==
        ">/sys/config.g(boot) M83 ?M98 ?>/sys/a.g(M98) ?M98 ?>/sys/b.g(M98) ?G1 ?< ?< "
        "?T0 ?>/sys/tpre0.g(tpre) ?G1 ?< ?=T0 ?M82 M84 <");
}

TEST_CASE("graph: the node limit cuts a run of commands where it falls", "[graph]") {
  const std::string config = "G1 X1\nif a\n  G1 X2\n  G1 X3\nG1 X4\nM98 P\"a.g\"\nG1 X5\n";
  const std::map<std::string, std::string> files{{"/sys/config.g", config}, {"/sys/a.g", "M83\nM84\n"}};
  CHECK(boot(*build(files)) == ">/sys/config.g(boot) G1 ?G1 ?G1 G1 M98 >/sys/a.g(M98) M83 M84 < G1 <");
  CHECK_FALSE(build(files)->graph.truncated);
  // The limit inside the block, at the M98, inside the called file: the run stops there, the files still leave.
  auto at3 = build(files, kLatestVersion, 3);
  CHECK(boot(*at3) == ">/sys/config.g(boot) G1 ?G1 <");
  CHECK(at3->graph.truncated);
  CHECK(boot(*build(files, kLatestVersion, 5)) == ">/sys/config.g(boot) G1 ?G1 ?G1 G1 <");
  CHECK(boot(*build(files, kLatestVersion, 8)) == ">/sys/config.g(boot) G1 ?G1 ?G1 G1 M98 >/sys/a.g(M98) M83 < <");
}

TEST_CASE("graph: an event repeated in the same call context is recorded once", "[graph]") {
  // config.g calls a.g twice, a.g calls b.g twice, b.g names a missing file twice (one line, two calls of it, each
  // the same context) and from an `if` once: the four runs of b.g meet the same three events. A 20-wide diamond of
  // this, 9 files deep, made millions of events (9 s, 1.6 GB) for findings that were the same.
  std::map<std::string, std::string> files{
      {"/sys/config.g", "M98 P\"a.g\"\nM98 P\"a.g\"\nM98 P\"b.g\"\n"},
      {"/sys/a.g", "M98 P\"b.g\"\nM98 P\"b.g\"\n"},
      {"/sys/b.g", "M98 P\"gone.g\"\nM98 P\"gone.g\"\nif a\n  M98 P\"gone.g\"\n"},
  };
  auto b = build(files);
  std::vector<std::string> events;
  for (const GraphEvent& e : b->graph.events) {
    const Node n = b->graph.nodes[e.node];
    events.push_back(
        fmt::format("{}:{}{} depth {}", b->machine->unit(n.unit).sd_path, n.index, n.maybe ? "?" : "", n.depth));
  }
  // From a.g (depth 3 in b.g), and from config.g's own call of b.g (depth 2): another context, recorded again.
  CHECK(events == std::vector<std::string>{"/sys/b.g:0 depth 3", "/sys/b.g:1 depth 3", "/sys/b.g:2? depth 3",
                                           "/sys/b.g:0 depth 2", "/sys/b.g:1 depth 2", "/sys/b.g:2? depth 2"});
}

TEST_CASE("graph: the node table decodes runs and whole nodes alike, at any id", "[graph]") {
  // A reference list of nodes: runs of commands of several lengths (some across the 4096-id steps of the run
  // index), broken by a change of file run, of maybe, by a gap in the command indices, and by whole nodes.
  std::vector<Node> want;
  NodeTable table;
  uint32_t index = 0;
  for (int k = 0; k < 200; ++k) {
    const uint32_t len = k % 7 == 0 ? 5000 : static_cast<uint32_t>(k % 5);
    Node c{NodeKind::Command,
           k % 3 == 0 ? CallKind::M98 : CallKind::Boot,
           k % 4 == 1,
           static_cast<uint16_t>(1 + k % 2),
           static_cast<uint32_t>(k % 3),
           index,
           static_cast<NodeId>(k),
           kNoNode};
    if (k % 2) {
      table.push_commands(c, len);  // a stretch at once,
    } else {
      for (uint32_t i = 0; i < len; ++i, ++c.index) table.push_back(c);  // or one by one
      c.index = index;
    }
    for (uint32_t i = 0; i < len; ++i, ++c.index) want.push_back(c);
    index += len + (k % 6 == 5 ? 3 : 0);  // sometimes a gap: a new run though all else is equal
    if (k % 5 == 2) {
      const Node other{NodeKind::ToolSelect, CallKind::Boot, false, 1, 0, 7, 0, static_cast<NodeId>(want.size() - 1)};
      table.push_back(other);
      want.push_back(other);
    }
  }
  REQUIRE(table.size() == want.size());
  CHECK(table.entries() < 400);
  auto same = [](const Node& a, const Node& b) {
    return a.kind == b.kind && a.call == b.call && a.maybe == b.maybe && a.depth == b.depth && a.unit == b.unit &&
           a.index == b.index && a.enter == b.enter && a.call_site == b.call_site;
  };
  size_t bad = 0;
  for (NodeId id = 0; id < want.size(); ++id) {
    if (!same(table[id], want[id])) ++bad;
    const NodeTable::Stretch st = table.stretch(id);
    if (st.begin > id || st.end <= id || !same(st.node, want[st.begin])) ++bad;
    // Every node of a stretch decodes like its first, one command further on.
    Node next = st.node;
    next.index += id - st.begin;
    if (!same(next, want[id])) ++bad;
  }
  CHECK(bad == 0);
  // find_if visits every node in order from anywhere, with the same values.
  for (NodeId from :
       {NodeId{0}, NodeId{1}, NodeId{4095}, NodeId{4096}, NodeId{12345}, static_cast<NodeId>(want.size() - 1)}) {
    NodeId expect = from;
    size_t wrong = 0;
    const NodeId hit = table.find_if(from, static_cast<NodeId>(want.size()), [&](NodeId id, const Node& n) {
      if (id != expect++ || !same(n, want[id])) ++wrong;
      return false;
    });
    CHECK(hit == kNoNode);
    CHECK(wrong == 0);
    CHECK(expect == want.size());
  }
  CHECK(table.find_if(10, 20000, [&](NodeId id, const Node&) { return id == 17777; }) == 17777);
  CHECK(table.find_if(10, 17777, [&](NodeId id, const Node&) { return id == 17777; }) == kNoNode);
  CHECK(table.find_if(5, 5, [](NodeId, const Node&) { return true; }) == kNoNode);
}

TEST_CASE("graph: files not reached at boot become entries", "[graph]") {
  auto b = build({
      {"/sys/config.g", "M98 P\"a.g\"\n"},
      {"/sys/a.g", "M83\n"},
      {"/sys/homeall.g", "G28 X\nM98 P\"a.g\"\n"},
      {"/sys/config.g.bak", "M82\n"},
      {"/sys/notes.txt", "not gcode\n"},
      {"/macros/Park head", "G1 X0\n"},
      {"/macros/.hidden.g", "G1 X0\n"},
      {"/filaments/PLA/load.g", "T0\n"},
      {"/sys/tpre0.g", "G4 S1\n"},
      {"/gcodes/part.gcode", "G1 X1\n"},
  });
  CHECK(boot(*b) == ">/sys/config.g(boot) M98 >/sys/a.g(M98) M83 < <");
  CHECK(entries(*b) == std::vector<std::string>{
                           ">/filaments/PLA/load.g(entry) T0 >/sys/tpre0.g(tpre) G4 < =T0 <",
                           ">/macros/Park head(entry) G1 <",
                           ">/sys/homeall.g(entry) G28 M98 >/sys/a.g(M98) M83 < <",
                           ">/sys/tpre0.g(entry) G4 <",
                       });
  // Without config.g every macro is an entry.
  auto lone = build({{"/macros/m.g", "M83\n"}});
  CHECK(boot(*lone) == "(no boot)");
  CHECK(entries(*lone) == std::vector<std::string>{">/macros/m.g(entry) M83 <"});
}

TEST_CASE("graph: Enter and Leave link to their call site", "[graph]") {
  auto b = build({{"/sys/config.g", "M83\nM98 P\"a.g\"\n"}, {"/sys/a.g", "G1 X1\n"}});
  const auto& n = b->graph.nodes;
  REQUIRE(n.size() == 7);
  CHECK(n[0].kind == NodeKind::Enter);
  CHECK(n[0].depth == 1);
  CHECK(n[0].call_site == kNoNode);
  CHECK(n[3].kind == NodeKind::Enter);
  CHECK(n[3].call_site == 2);
  CHECK(n[3].enter == 0);
  CHECK(n[3].depth == 2);
  CHECK(n[4].enter == 3);
  CHECK(n[5].kind == NodeKind::Leave);
  CHECK(n[5].enter == 3);
  CHECK(n[6].kind == NodeKind::Leave);
  REQUIRE(b->graph.segments.size() == 1);
  CHECK(b->graph.segments[0].begin == 0);
  CHECK(b->graph.segments[0].end == 7);
}

TEST_CASE("graph: SD paths join and fold the way RRF's CombineName does", "[graph]") {
  auto r = [](std::string_view dir, std::string_view name) { return resolve_sd_path(dir, name).value_or("<none>"); };
  CHECK(r("/sys", "tpost0.g") == "/sys/tpost0.g");  // the plain case
  CHECK(r("/sys", "macros/park.g") == "/sys/macros/park.g");
  CHECK(r("/sys", "/macros/park.g") == "/macros/park.g");    // absolute
  CHECK(r("/sys", "0:/macros/park.g") == "/macros/park.g");  // volume 0
  CHECK(r("/sys", "0:macros/park.g") == "/macros/park.g");
  CHECK(r("/sys", "1:/x.g") == "<none>");                    // another volume
  CHECK(r("/sys", "../macros/park.g") == "/macros/park.g");  // folded
  CHECK(r("/sys", "./a/./b.g") == "/sys/a/b.g");
  CHECK(r("/sys", "a//b.g") == "/sys/a/b.g");
  CHECK(r("/sys/", "a.g") == "/sys/a.g");
  CHECK(r("/", "a.g") == "/a.g");
  CHECK(r("/sys/sub", "..") == "/sys");
  CHECK(r("/sys", "a..b.g") == "/sys/a..b.g");  // dots inside a name are a name
  bool outside = false;
  CHECK_FALSE(resolve_sd_path("/sys", "../../x.g", &outside));
  CHECK(outside);
}

TEST_CASE("lint: threads report the same for files the graph loads while file rules run", "[graph]") {
  // A large machine starts the file rules that read one file while the graph is built; the files the graph loads
  // (here one outside the listed folders) and the rules that read the machine (unknown-command, the parenthesis
  // rule) wait for it. Run with parts of a few bytes, so that this small card takes the parallel path.
  auto lint = [](unsigned threads) {
    MemoryReader reader;
    reader.add("/sys/config.g",
               "M98 P\"/gcodes/start.g\"\nM117 \"x\"\nG1 X1 (note) Y2 ; rrflint: disable=RRF999\nM4321\n");
    reader.add("/sys/homeall.g", "G1 X1 'a' ; text\nM4322\n");
    reader.add("/gcodes/start.g", "M4323 ; not a command\nG1 X(1) Y1\nM117 \"it's\"\nG1 X1e5\n");
    LintOptions o;
    o.select = {"ALL"};
    o.threads = threads;
    o.part_bytes = 8;
    SourceManager sources;
    MachineResult r = lint_machine(sources, reader, builtin_rules(), o);
    std::vector<std::string> out;
    for (const Diagnostic& d : r.diagnostics)
      out.push_back(sources.get(d.loc.file).sd_path() + " " + std::to_string(d.loc.span.begin) + " " +
                    std::string(d.code) + " " + d.message);
    return out;
  };
  const std::vector<std::string> serial = lint(1);
  auto has = [&](std::string_view file, std::string_view code) {
    return std::any_of(serial.begin(), serial.end(), [&](const std::string& s) {
      return s.starts_with(file) && s.find(std::string(" ") + std::string(code) + " ") != std::string::npos;
    });
  };
  CHECK(has("/gcodes/start.g", "RRF101"));  // unknown-command in the file the graph loaded
  CHECK(has("/sys/homeall.g", "RRF101"));
  CHECK(has("/sys/config.g", "RRF901"));  // a suppression of an unknown rule
  for (unsigned threads : {2u, 3u}) CHECK(lint(threads) == serial);
}

TEST_CASE("graph: a branch known at boot runs for certain or not at all", "[graph]") {
  auto b = build({{"/sys/config.g",
                   "global mode = \"idex\"\n"
                   "if global.mode == \"idex\"\n  M98 P\"idex.g\"\nelse\n  M98 P\"single.g\"\n"
                   "if directories.system != \"0:/sys/\"\n  M83\nelif !false\n  M82\n  if move.axes[0].homed\n    G28\n"
                   "if move.axes[0].homed\n  M84\nelse\n  M17\n"},
                  {"/sys/idex.g", "M584 U3\n"},
                  {"/sys/single.g", "M584 X0\n"}});
  // The else of a known condition, and the if known false, do not run; a nested unknown if stays maybe, as does a
  // chain whose condition is not known.
  CHECK(boot(*b) == ">/sys/config.g(boot) M98 >/sys/idex.g(M98) M584 < M82 ?G28 ?M84 ?M17 <");
}
