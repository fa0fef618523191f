#pragma once
// A FitnessReport as JSON: the one form that checkpoints, run results (champion.json) and the
// evaluation wire between MPI ranks all use.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness.hpp"

namespace bhm::evo {

//! A behaviour descriptor: empty (diverged, or written before descriptors) or kBehaviourLength
//! numbers. Throws FieldError naming WHERE otherwise.
std::vector<double> behaviour_from_json(const nlohmann::json& json, const std::string& where);

nlohmann::json report_to_json(const FitnessReport& report);
//! Throws FieldError (json_fields.hpp) "LABEL.field: message" on anything missing or of the
//! wrong type.
FitnessReport report_from_json(const nlohmann::json& json, const std::string& label);

}  // namespace bhm::evo
