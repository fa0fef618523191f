#include "evo/run/rule_change_json.hpp"

#include <array>
#include <stdexcept>

#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"
#include "evo/run/loop_check_json.hpp"
#include "evo/run/physics_rules.hpp"

namespace bhm::evo {

using nlohmann::json;

namespace {

using Context = RuleChangeContext;
using Field = JsonField<RuleChange, Context>;

//! A reader's error as a FieldError naming `where` once (the experiment's and the physics'
//! readers already start their messages with the label they are given).
[[noreturn]] void fail_at(const std::string& where, const std::exception& e) {
    const std::string message = e.what();
    throw FieldError(message.rfind(where, 0) == 0 ? message : where + ": " + message);
}

//! The fitness section as the experiment file writes it, beside the rest of `base`.
void write_fitness(const RuleChange& c, const char* key, json& out, const Context& context) {
    Experiment e = context.base;
    e.fitness = c.fitness;
    out[key] = experiment_to_json(e)["fitness"];
}
//! The fitness section alone, read through the experiment reader against the base.
void read_fitness(const Fields& f, const Field& field, RuleChange& c, Context& context) {
    json e = experiment_to_json(context.base);
    e["fitness"] = f.at(field.key);
    const std::string where = f.join(field.key);
    try {
        c.fitness = parse_experiment(e, where).fitness;
    } catch (const std::exception& ex) {
        fail_at(where, ex);
    }
}

void write_physics(const RuleChange& c, const char* key, json& out, const Context& context) {
    if (c.physics) out[key] = physics_to_json(*c.physics, context.base);
}
void read_physics(const Fields& f, const Field& field, RuleChange& c, Context& context) {
    if (field.skipped(f, context)) return;
    const std::string where = f.join(field.key);
    try {
        c.physics = physics_from_json(f.at(field.key), context.base, where);
    } catch (const FieldError&) {
        throw;
    } catch (const std::exception& e) {
        fail_at(where, e);
    }
}

void write_verify(const RuleChange& c, const char* key, json& out, const Context&) {
    if (c.verify) out[key] = loop_verify_settings_to_json(*c.verify);
}
void read_verify(const Fields& f, const Field& field, RuleChange& c, Context& context) {
    if (field.skipped(f, context)) return;
    c.verify = loop_verify_settings_from_json(f.at(field.key), f.join(field.key));
}

constexpr std::array kRuleChange = {
    member_field<&RuleChange::generation, Context>("generation", 1, "",
                                                   "the first generation under it"),
    Field{"fitness", "fitness", 1, "",
          "the fitness section in force from then, as the experiment file writes it", write_fitness,
          read_fitness},
    Field{"physics", "physics", 3, "a change that set the physics",
          "materials, actuation and damping (evo/run/physics_rules.hpp)", write_physics,
          read_physics},
    Field{"verify", "verify settings", 3, "a change that set the continuum checks", "their policy",
          write_verify, read_verify},
};

}  // namespace

std::span<const JsonField<RuleChange, RuleChangeContext>> rule_change_fields() {
    return kRuleChange;
}

json rule_change_to_json(const RuleChange& c, const Experiment& base) {
    return write_fields(kRuleChange, c, Context{base});
}

RuleChange rule_change_from_json(const json& j, const Experiment& base, const std::string& where) {
    Context context{base};
    RuleChange change;
    read_fields(kRuleChange, Fields(j, where), change, context);
    return change;
}

json rule_changes_to_json(const std::vector<RuleChange>& changes, const Experiment& base) {
    return write_objects<rule_change_fields>(changes, Context{base});
}

std::vector<RuleChange> rule_changes_from_json(const json& j, const Experiment& base,
                                               const std::string& where) {
    Context context{base};
    return read_objects<rule_change_fields, RuleChange>(j, where, context);
}

}  // namespace bhm::evo
