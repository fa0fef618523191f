#include "evo/run/rule_change_json.hpp"

#include <stdexcept>

#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/run/loop_check_json.hpp"
#include "evo/run/physics_rules.hpp"

namespace bhm::evo {

using nlohmann::json;

namespace {

//! A reader's error as a FieldError naming `where` once (the experiment's and the physics'
//! readers already start their messages with the label they are given).
[[noreturn]] void fail_at(const std::string& where, const std::exception& e) {
    const std::string message = e.what();
    throw FieldError(message.rfind(where, 0) == 0 ? message : where + ": " + message);
}

//! The fitness section alone, read through the experiment reader against `base`.
Fitness fitness_from_json(const json& fitness, const Experiment& base, const std::string& where) {
    json e = experiment_to_json(base);
    e["fitness"] = fitness;
    try {
        return parse_experiment(e, where).fitness;
    } catch (const std::exception& ex) {
        fail_at(where, ex);
    }
}

}  // namespace

json rule_change_to_json(const RuleChange& c, const Experiment& base) {
    Experiment e = base;
    e.fitness = c.fitness;
    json change = {{"generation", c.generation}, {"fitness", experiment_to_json(e)["fitness"]}};
    if (c.physics) change["physics"] = physics_to_json(*c.physics, base);
    if (c.verify) change["verify"] = loop_verify_settings_to_json(*c.verify);
    return change;
}

RuleChange rule_change_from_json(const json& j, const Experiment& base, const std::string& where) {
    const Fields f(j, where);
    RuleChange change{static_cast<int>(f.integer("generation")),
                      fitness_from_json(f.at("fitness"), base, f.join("fitness")), std::nullopt,
                      std::nullopt};
    if (j.contains("physics")) {
        try {
            change.physics = physics_from_json(j.at("physics"), base, f.join("physics"));
        } catch (const FieldError&) {
            throw;
        } catch (const std::exception& e) {
            fail_at(f.join("physics"), e);
        }
    }
    if (j.contains("verify"))
        change.verify = loop_verify_settings_from_json(j.at("verify"), f.join("verify"));
    return change;
}

json rule_changes_to_json(const std::vector<RuleChange>& changes, const Experiment& base) {
    json out = json::array();
    for (const auto& c : changes)
        out.push_back(rule_change_to_json(c, base));
    return out;
}

std::vector<RuleChange> rule_changes_from_json(const json& j, const Experiment& base,
                                               const std::string& where) {
    if (!j.is_array()) throw FieldError(where + ": expected an array");
    std::vector<RuleChange> out;
    for (std::size_t i = 0; i < j.size(); ++i)
        out.push_back(rule_change_from_json(j[i], base, item(where, i)));
    return out;
}

}  // namespace bhm::evo
