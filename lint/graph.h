// The ordered command graph: the boot sequence in execution order, and every other macro as an entry.
//
// config.g runs first, with each M98 file inlined at its call site (relative to /sys or the M505 folder),
// config-override.g at the M501, the tool-change macros that a `T` runs, then runonce.g. Every other .g
// file under /sys, /macros and /filaments becomes an entry of its own that starts from the end-of-boot
// machine state (rrf-semantics §2.9, §4).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "firmware.h"
#include "project.h"

namespace rrflint {

using NodeId = uint32_t;
inline constexpr NodeId kNoNode = UINT32_MAX;

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

/// The nodes of a graph, in execution order. A command node is stored in 8 bytes (its command index and the
/// file run it belongs to); elements are decoded into `Node` values on access, so bind them as `const Node&`
/// and keep NodeIds, not pointers.
class NodeTable {
 public:
  Node operator[](NodeId id) const {
    const Rec& r = recs_[id];
    if (r.b == kFull) return full_[r.a];
    const Frame& f = frames_[r.a];
    return Node{NodeKind::Command, f.call, (r.b & kMaybe) != 0, f.depth, f.unit, r.b & ~kMaybe, f.enter, kNoNode};
  }
  size_t size() const { return recs_.size(); }
  bool empty() const { return recs_.empty(); }
  DecodingIterator<NodeTable, Node> begin() const { return {this, 0}; }
  DecodingIterator<NodeTable, Node> end() const { return {this, size()}; }
  void push_back(const Node& n);
  void reserve(size_t n);

 private:
  static constexpr uint32_t kFull = UINT32_MAX, kMaybe = 1u << 31;
  struct Rec {
    uint32_t a;  // command: the frame; otherwise an index into full_
    uint32_t b;  // command: index | kMaybe; otherwise kFull
  };
  struct Frame {  // what the command nodes of one stretch of a file run share
    CallKind call;
    uint16_t depth;
    uint32_t unit;
    NodeId enter;
  };
  std::vector<Rec> recs_;
  std::vector<Frame> frames_;
  std::vector<Node> full_;
};

struct Graph {
  NodeTable nodes;
  std::vector<Segment> segments;
  std::vector<GraphEvent> events;
  bool truncated = false;  // stopped at the node limit
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
