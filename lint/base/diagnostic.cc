#include "lint/base/diagnostic.h"

#include "lint/base/strings.h"

namespace rrflint {

std::string_view severity_name(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Info: return "info";
  }
  return "?";
}

std::optional<Severity> parse_severity(std::string_view s) {
  std::string l = to_lower(s);
  if (l == "error") return Severity::Error;
  if (l == "warning") return Severity::Warning;
  if (l == "info") return Severity::Info;
  return std::nullopt;
}

std::string_view applicability_name(Applicability a) { return a == Applicability::Safe ? "safe" : "unsafe"; }

}  // namespace rrflint
