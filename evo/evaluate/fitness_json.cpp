#include "evo/evaluate/fitness_json.hpp"

#include <stdexcept>
#include <vector>

#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/exploit_flags.hpp"
#include "evo/experiment/json_fields.hpp"

namespace bhm::evo {

using nlohmann::json;

std::vector<double> behaviour_from_json(const json& j, const std::string& where) {
    if (!j.is_array() || (!j.empty() && j.size() != static_cast<std::size_t>(kBehaviourLength)))
        throw FieldError(where + ": expected an empty array or " +
                         std::to_string(kBehaviourLength) + " numbers");
    std::vector<double> values;
    values.reserve(j.size());
    for (const auto& v : j) {
        if (!v.is_number()) throw FieldError(where + ": expected numbers");
        values.push_back(v.get<double>());
    }
    return values;
}

FitnessReport report_from_json(const json& j, const std::string& path) {
    const Fields f(j, path);
    FitnessReport r;
    r.fitness = f.number("fitness");
    const Fields m(f.at("measures"), f.join("measures"));
    for (std::size_t k = 0; k < r.measures.size(); ++k)
        r.measures[k] = m.number(kFitnessNames[k]);
    r.diverged = f.boolean("diverged");
    r.divergence_reason = f.string("divergence_reason");
    r.simulated_s = f.number("simulated_s");
    r.steps = f.integer("steps");
    r.sim_wall_s = f.number("sim_wall_s");
    if (j.contains("exploits")) {  // absent in checkpoints written before exploit detection
        try {
            r.exploits = exploits_from_json(j.at("exploits"));
        } catch (const std::invalid_argument& e) {
            throw FieldError(path + "." + e.what());
        }
    }
    if (j.contains("behaviour"))  // absent in results written before behaviour descriptors
        r.behaviour = behaviour_from_json(j.at("behaviour"), f.join("behaviour"));
    // Absent in results written before evaluations could end early (they ran the full time).
    if (j.contains("ended_early")) r.ended_early = f.boolean("ended_early");
    if (j.contains("periodic_residual")) r.periodic_residual = f.number("periodic_residual");
    return r;
}

json report_to_json(const FitnessReport& r) {
    json measures = json::object();
    for (std::size_t k = 0; k < r.measures.size(); ++k)
        measures[kFitnessNames[k]] = r.measures[k];
    return {{"fitness", r.fitness},
            {"measures", measures},
            {"diverged", r.diverged},
            {"divergence_reason", r.divergence_reason},
            {"simulated_s", r.simulated_s},
            {"steps", r.steps},
            {"sim_wall_s", r.sim_wall_s},
            {"exploits", exploits_to_json(r.exploits)},
            {"behaviour", r.behaviour},
            {"ended_early", r.ended_early},
            {"periodic_residual", r.periodic_residual}};
}

}  // namespace bhm::evo
