// The numbered objects of the model a command's parameters name (tools, heaters, fans, sensors), and how the
// language server describes them: for hover (what the command touches) and completion (the numbers that exist).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cli/server/model_at.h"

namespace rrflint::server {

enum class ObjKind : uint8_t { Tool, Heater, Fan, Sensor };
std::string_view obj_kind_name(ObjKind k);  // "tool", "heater", …

/// A parameter that names an object by number: `G10 P`, `M143 H`, `M950 T` (a sensor) … For `T<n>` the letter is
/// 'T' and the number is the command's own. `creates`: the command creates (or re-creates) the object.
struct ObjectParam {
  char letter;  // of the command
  int number;   // of the command (-1 for T)
  char param;
  ObjKind kind;
  bool creates;
};

/// The object parameter `param` of a command, or null. (G10 P names a tool only in its L1 form, or with no L.)
const ObjectParam* object_param(const ParsedFile& pf, const Command& c, char param);
/// Every object parameter a command has (for T: the tool it selects).
std::vector<const ObjectParam*> object_params(const ParsedFile& pf, const Command& c);

/// `s` as a Markdown code span when `code`, else as it is.
std::string code_span(std::string_view s, bool code);
/// One line about object n in state `s`: "tool 1 "Right" (created at sys/config.g:5)", or nullopt when it does
/// not exist there. `code` wraps file positions and names (Markdown code spans, or nothing for plain text).
std::optional<std::string> describe(const DocAt& d, const MachineState& s, ObjKind k, int n, bool code);
/// The numbers of the objects of kind k in `s`, in order.
std::vector<int> object_numbers(const MachineState& s, ObjKind k);
/// Does the model know every object of this kind in `s` (no number came from an expression or a lone macro)?
bool objects_known(const MachineState& s, ObjKind k);
/// Tool n's axis maps and offsets, as lines (for G10 P and T hovers); empty when it does not exist.
std::vector<std::string> tool_details(const DocAt& d, const MachineState& s, int n, bool code);

/// What an M584 (the axes it names: their drivers, or that it creates them) or an M569 (which axis or extruder
/// each of its drivers moves) touches in `s`, as lines; empty for other commands.
std::vector<std::string> drive_facts(const DocAt& d, const MachineState& s, const Command& c, bool code);

}  // namespace rrflint::server
