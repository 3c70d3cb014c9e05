// The ordered command graph: the boot sequence in execution order, and every other macro as an entry.
//
// config.g runs first, with each M98 file inlined at its call site (relative to /sys or the M505 folder),
// config-override.g at the M501, the tool-change macros that a `T` runs, then runonce.g. Every other .g
// file under /sys, /macros and /filaments becomes an entry of its own that starts from the end-of-boot
// machine state (docs/firmware-behaviour.md#m98-and-macros, #system-files).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lint/boot/firmware.h"
#include "lint/card/card.h"

namespace rrflint {

using NodeId = uint32_t;
inline constexpr NodeId kNoNode = UINT32_MAX;

// Which tool is selected, as the graph builder follows T commands and as MachineState::current_tool records it.
inline constexpr int kNoTool = -1;       // none: T-1, the start of config.g, or a T for a tool that does not exist
inline constexpr int kUnknownTool = -2;  // the graph builder cannot tell: T{…}, a T in an if/while, an entry's start
/// A ToolSelect node's `index` when its T names no tool: a deselect (T-1) or a tool the graph builder cannot know
/// (T{…}, an unknown P); the call site's command tells them apart.
inline constexpr uint32_t kNoToolNumber = UINT32_MAX;

enum class NodeKind : uint8_t {
  Command,     // one G/M/T command of a file
  Enter,       // a file starts running
  Leave,       // a file finished
  ToolSelect,  // the moment a T command selects its tool (between tpre and tpost)
};

enum class CallKind : uint8_t { Boot, Entry, M98, M501, RunOnce, ToolFree, ToolPre, ToolPost };
std::string_view call_kind_name(CallKind k);

struct Node {
  NodeKind kind = NodeKind::Command;
  CallKind call = CallKind::Boot;  // Enter/Leave: why the file runs
  bool maybe = false;              // inside an if/else branch or loop here or in a caller: effects are *maybe*
  uint16_t depth = 0;              // macro nesting: config.g and entries are 1
  uint32_t unit = 0;               // the FileUnit (Machine::unit) this node belongs to
  uint32_t index = 0;              // Command: index into the unit's commands; ToolSelect/tool macros: tool number
                                   // (ToolSelect: kNoToolNumber if none is known)
  NodeId enter = kNoNode;          // the Enter node of the file run this node belongs to
  NodeId call_site = kNoNode;      // Enter: the Command node that called the file (M98, M501, T)
};

struct GraphEvent {
  enum class Kind : uint8_t { MissingFile, Cycle, TooDeep, OutsideRoot, OtherVolume, UnreadableFile } kind;
  NodeId node;       // the calling command
  std::string path;  // the SD path involved
  int limit = 0;     // TooDeep: the nesting limit
};

struct Segment {
  NodeId begin = 0, end = 0;  // node range [begin, end)
  uint32_t unit = 0;          // the entry file
  bool boot = false;          // the boot sequence (config.g …) rather than a standalone entry
};

/// The nodes of a graph, in execution order. Command nodes are stored as runs: a stretch of consecutive commands of
/// one file run that share their `maybe` is one 12-byte entry, however long (a 100 MB config.g with no blocks is a
/// handful of runs). Other nodes are stored whole. Elements are decoded into `Node` values on access, so bind them
/// as `const Node&` and keep NodeIds, not pointers. Access by id finds the run through a table of the run at every
/// 4096th id, then a search among the runs of that stretch (one step in practice).
class NodeTable {
 public:
  Node operator[](NodeId id) const { return decode(run_of(id), id); }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  DecodingIterator<NodeTable, Node> begin() const { return {this, 0}; }
  DecodingIterator<NodeTable, Node> end() const { return {this, size()}; }
  void push_back(const Node& n);
  /// Appends the command nodes of commands [n.index, n.index + count) of one file run, all like `n` (its kind is
  /// Command, its call_site kNoNode).
  void push_commands(const Node& n, uint32_t count);

  /// A stretch of nodes [begin, end) that decode alike: a run of command nodes (`node` is the first; the others
  /// differ only in `index`, one more each) or one other node. stretch(id) is the one holding `id`.
  struct Stretch {
    NodeId begin, end;
    Node node;
  };
  Stretch stretch(NodeId id) const {
    const size_t r = run_of(id);
    const NodeId end = r + 1 < runs_.size() ? runs_[r + 1].first : static_cast<NodeId>(size_);
    return Stretch{runs_[r].first, end, decode(r, runs_[r].first)};
  }
  /// The first node of [from, to) for which f(id, node) holds, visiting them in order (a run at a time, with no
  /// search per node), or kNoNode.
  template <class F>
  NodeId find_if(NodeId from, NodeId to, F f) const {
    to = std::min<NodeId>(to, static_cast<NodeId>(size_));
    if (from >= to) return kNoNode;
    for (size_t r = run_of(from); r < runs_.size() && runs_[r].first < to; ++r) {
      const NodeId end = std::min<NodeId>(to, r + 1 < runs_.size() ? runs_[r + 1].first : static_cast<NodeId>(size_));
      NodeId id = std::max(from, runs_[r].first);
      Node n = decode(r, id);
      for (; id < end; ++id, ++n.index)
        if (f(id, static_cast<const Node&>(n))) return id;
    }
    return kNoNode;
  }
  /// Calls f(id, node) for each node stored whole (every node but a command: Enter, Leave, ToolSelect), in order.
  template <class F>
  void each_whole(F f) const {
    for (size_t r = 0; r < runs_.size(); ++r)
      if (runs_[r].frame == kFull) f(runs_[r].first, static_cast<const Node&>(decode(r, runs_[r].first)));
  }
  /// How many entries the table keeps (tests and traces: runs and whole nodes).
  size_t entries() const { return runs_.size(); }
  /// Calls f(first, unit, index, count) for each run of command nodes, in order: nodes [first, first + count) run
  /// commands [index, index + count) of `unit`.
  template <class F>
  void each_command_run(F f) const {
    for (size_t r = 0; r < runs_.size(); ++r) {
      if (runs_[r].frame == kFull) continue;
      const NodeId end = r + 1 < runs_.size() ? runs_[r + 1].first : static_cast<NodeId>(size_);
      f(runs_[r].first, frames_[runs_[r].frame].unit, runs_[r].index, end - runs_[r].first);
    }
  }

 private:
  static constexpr uint32_t kFull = UINT32_MAX;
  static constexpr unsigned kBlockBits = 12;
  struct Run {
    NodeId first;    // the id of its first node
    uint32_t frame;  // command nodes: the frame; kFull: one node, stored whole
    uint32_t index;  // command nodes: the first command's index; kFull: the index into full_
  };
  struct Frame {  // what the command nodes of one stretch of a file run share
    CallKind call;
    bool maybe;
    uint16_t depth;
    uint32_t unit;
    NodeId enter;
  };
  size_t run_of(NodeId id) const {
    const size_t b = id >> kBlockBits;
    size_t lo = block_runs_[b];
    const size_t hi = b + 1 < block_runs_.size() ? block_runs_[b + 1] : runs_.size() - 1;
    // The last run in [lo, hi] that starts at or before id.
    size_t count = hi - lo;
    while (count > 0) {
      const size_t half = (count + 1) / 2;
      if (runs_[lo + half].first <= id) {
        lo += half;
        count -= half;
      } else {
        count = half - 1;
      }
    }
    return lo;
  }
  Node decode(size_t r, NodeId id) const {
    const Run& run = runs_[r];
    if (run.frame == kFull) return full_[run.index];
    const Frame& f = frames_[run.frame];
    return Node{NodeKind::Command, f.call, f.maybe, f.depth, f.unit, run.index + (id - run.first), f.enter, kNoNode};
  }
  void grow(size_t n);  // size_ += n, keeping block_runs_
  std::vector<Run> runs_;
  std::vector<Frame> frames_;
  std::vector<Node> full_;
  std::vector<uint32_t> block_runs_;  // the run holding id k << kBlockBits
  size_t size_ = 0;
};

class GraphCache;

struct Graph {
  Graph();
  ~Graph();
  Graph(Graph&&) noexcept;
  Graph& operator=(Graph&&) noexcept;
  NodeTable nodes;
  std::vector<Segment> segments;
  std::vector<GraphEvent> events;
  bool truncated = false;  // stopped at the node limit
  /// The M98 nodes whose path is an expression known at boot (lint/boot/const_eval.h), in order: the graph
  /// followed them, so the model need not take them as "anything may happen".
  std::vector<NodeId> evaluated_calls;
  bool evaluated(NodeId id) const { return std::binary_search(evaluated_calls.begin(), evaluated_calls.end(), id); }
  /// The command nodes that run a command of this code (any fraction), in order; nullptr for a number outside
  /// 0…1023, which has no index (walk the nodes then). Built for a code the first time it is asked for, from each
  /// file's code index (ParsedFile::with_code), at a cost in the runs of the graph and the code's commands: a rule
  /// that looks for "the next M950" jumps to it instead of walking every node to the end. Thread-safe; the graph must
  /// not change afterwards.
  const std::vector<NodeId>* code_nodes(const Machine& m, char letter, int32_t number) const;
  /// A value derived from the graph (an index that a rule builds once rather than walking the nodes for each
  /// command it checks), built by `build()` the first time `key` is asked for and kept with the graph. Thread-safe:
  /// rules run in parallel; a build may ask for other derived values or code_nodes.
  template <class T, class Build>
  const T& derived(const std::string& key, Build build) const {
    std::lock_guard<std::recursive_mutex> lock(derived_mutex());
    std::shared_ptr<void>& slot = derived_slot(key);
    if (!slot) slot = std::make_shared<T>(build());
    return *static_cast<const T*>(slot.get());
  }

 private:
  std::recursive_mutex& derived_mutex() const;
  std::shared_ptr<void>& derived_slot(const std::string& key) const;
  std::unique_ptr<GraphCache> cache_;  // code_nodes and derived
};

struct GraphOptions {
  Version firmware;
  std::string sys_dir = "/sys";
  bool include_entries = true;  // lint every other macro as an entry
  size_t max_nodes = 4'000'000;
};

/// Builds the graph for the machine whose config.g is `/sys/config.g` (if present) plus all entries.
Graph build_graph(Machine& machine, const GraphOptions& opts);

/// Candidate macro files of a machine: /sys/**.g, /macros/** (.g or no extension), /filaments/**.g.
std::vector<std::string> machine_files(FileReader& reader, const std::string& sys_dir);

}  // namespace rrflint
