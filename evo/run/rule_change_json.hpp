#pragma once
// A run's rule changes as JSON: the one form that run.json and the checkpoint both write and read
// (issue 41), walked from one field table (json_schema.hpp). Each change is {generation, fitness,
// physics?, verify?}: `fitness` is the experiment file's fitness section, `physics`
// physics_to_json's object, `verify` the continuum checks' policy. The fitness and physics
// sections are written and read against `base`, the experiment of the file that holds them
// (run.json: the experiment as started; the checkpoint: the rules in force), since they are parts
// of an experiment file and read through its reader.
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"
#include "evo/run/json_schema.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::evo {

struct RuleChangeContext {
    const Experiment& base;
    //! The form has no versions of its own: the fields added later (since > 1) are optional.
    int version = 1;
};

//! The fields of one change; their `since` is the checkpoint format that added them.
std::span<const JsonField<RuleChange, RuleChangeContext>> rule_change_fields();

nlohmann::json rule_change_to_json(const RuleChange& change, const Experiment& base);
//! Throws FieldError (json_fields.hpp) "WHERE.field: message".
RuleChange rule_change_from_json(const nlohmann::json& j, const Experiment& base,
                                 const std::string& where);

nlohmann::json rule_changes_to_json(const std::vector<RuleChange>& changes, const Experiment& base);
//! An array of rule_change_to_json's objects; element i is named "WHERE[i]" in errors.
std::vector<RuleChange> rule_changes_from_json(const nlohmann::json& j, const Experiment& base,
                                               const std::string& where);

}  // namespace bhm::evo
