#pragma once
// The continuum checks of the loop as JSON: the checks kept in a checkpoint and the policy a rule
// change set (checkpoint.json and run.json). Doubles are written in full, so a resumed run reads
// back exactly what the uninterrupted one holds.
#include <string>

#include <nlohmann/json.hpp>

#include "evo/run/loop_check.hpp"

namespace bhm::evo {

nlohmann::json loop_check_to_json(const LoopCheck& check);
//! Throws FieldError (json_fields.hpp) naming `path` and the field.
LoopCheck loop_check_from_json(const nlohmann::json& j, const std::string& path);

//! The picks waiting to land, each body whole (the body file's form): a resumed run checks them
//! even where the individuals have left the population.
nlohmann::json pending_checks_to_json(const PendingChecks& pending);
PendingChecks pending_checks_from_json(const nlohmann::json& j, const std::string& path);

nlohmann::json loop_verify_settings_to_json(const LoopVerifySettings& settings);
LoopVerifySettings loop_verify_settings_from_json(const nlohmann::json& j,
                                                  const std::string& path);

nlohmann::json loop_check_row_to_json(const LoopCheckRow& row);
LoopCheckRow loop_check_row_from_json(const nlohmann::json& j, const std::string& path);

}  // namespace bhm::evo
