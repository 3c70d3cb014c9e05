// The parts of `rrflint model` beyond the first tables (lint/render/model_tables.cc), and the helpers both files
// use: a fact's source line, numbers, aligned tables.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lint/engine/linter.h"

namespace rrflint::model_text {

/// "sys/config.g:12" for the command of node `id`, "default" for kNoNode.
std::string where(const MachineResult& r, const SourceManager& sm, NodeId id);
/// A number with up to three decimals, trailing zeros cut ("0.5", "80").
std::string num(double v);
/// A fact's value, or "unknown".
std::string fact(const Fact& f);
/// Aligned columns, indented two spaces; rows[0] is the header.
void table(std::ostream& os, const std::vector<std::vector<std::string>>& rows);
/// A fact as JSON: its number, or "unknown".
nlohmann::json fact_json(const Fact& f);
/// Node `id` as JSON: where(), or null for kNoNode.
nlohmann::json at_json(const MachineResult& r, const SourceManager& sm, NodeId id);

/// Heater monitor slots, PID and fault detection; drivers, drives and endstops; ports, triggers and filament
/// monitors; kinematics and leadscrews, as text tables.
void render_heater_settings(std::ostream& os, const SourceManager& sm, const MachineResult& r);
void render_drives(std::ostream& os, const SourceManager& sm, const MachineResult& r);
void render_ports(std::ostream& os, const SourceManager& sm, const MachineResult& r);
void render_kinematics(std::ostream& os, const SourceManager& sm, const MachineResult& r);

/// The JSON fields these add: to one heater, fan, probe or axis object, and to the document.
void heater_json(nlohmann::json& j, const SourceManager& sm, const MachineResult& r, const Heater& h);
void fan_json(nlohmann::json& j, const SourceManager& sm, const MachineResult& r, const Fan& f);
void probe_json(nlohmann::json& j, const SourceManager& sm, const MachineResult& r, const Probe& p);
void axis_json(nlohmann::json& j, const SourceManager& sm, const MachineResult& r, const Axis& a);
void machine_json(nlohmann::json& j, const SourceManager& sm, const MachineResult& r);

}  // namespace rrflint::model_text
