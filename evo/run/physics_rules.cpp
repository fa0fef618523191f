#include "evo/run/physics_rules.hpp"

#include <cstdio>
#include <stdexcept>

#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo {

using nlohmann::json;

PhysicsRules physics_of(const Experiment& experiment) {
    PhysicsRules p;
    for (const auto& m : experiment.materials)
        p.materials.push_back(m.physics);
    p.frequency_hz = experiment.actuation.frequency_hz;
    p.temperature_amplitude_c = experiment.actuation.temperature_amplitude_c;
    p.phase_offset_rad = experiment.actuation.phase_offset_rad;
    p.bond_damping_ratio = experiment.simulation.bond_damping_ratio;
    p.global_damping_ratio = experiment.simulation.global_damping_ratio;
    return p;
}

Experiment with_physics(const Experiment& experiment, const PhysicsRules& physics) {
    if (physics.materials.size() != experiment.materials.size())
        throw std::invalid_argument("physics change: " + std::to_string(physics.materials.size()) +
                                    " materials for an experiment with " +
                                    std::to_string(experiment.materials.size()));
    Experiment e = experiment;
    for (std::size_t i = 0; i < e.materials.size(); ++i) {
        const bool was_active = e.materials[i].active();
        e.materials[i].physics = physics.materials[i];
        if (e.materials[i].active() != was_active)
            throw std::invalid_argument("physics change: materials[" + std::to_string(i) +
                                        "].cte_per_c would make material '" +
                                        e.materials[i].name + "' " +
                                        (was_active ? "passive" : "active") +
                                        " (the run's bodies would change)");
    }
    e.actuation.frequency_hz = physics.frequency_hz;
    e.actuation.temperature_amplitude_c = physics.temperature_amplitude_c;
    e.actuation.phase_offset_rad = physics.phase_offset_rad;
    e.simulation.bond_damping_ratio = physics.bond_damping_ratio;
    e.simulation.global_damping_ratio = physics.global_damping_ratio;
    const auto problems = validate_experiment(e, "physics change");
    if (!problems.empty()) throw std::invalid_argument(problems.front().to_string());
    return e;
}

json physics_to_json(const PhysicsRules& physics, const Experiment& base) {
    Experiment e = base;
    for (std::size_t i = 0; i < e.materials.size() && i < physics.materials.size(); ++i)
        e.materials[i].physics = physics.materials[i];
    e.actuation.frequency_hz = physics.frequency_hz;
    e.actuation.temperature_amplitude_c = physics.temperature_amplitude_c;
    e.actuation.phase_offset_rad = physics.phase_offset_rad;
    e.simulation.bond_damping_ratio = physics.bond_damping_ratio;
    e.simulation.global_damping_ratio = physics.global_damping_ratio;
    const json j = experiment_to_json(e);
    return {{"materials", j.at("materials")},
            {"actuation", j.at("actuation")},
            {"simulation",
             {{"bond_damping_ratio", j.at("simulation").at("bond_damping_ratio")},
              {"global_damping_ratio", j.at("simulation").at("global_damping_ratio")}}}};
}

PhysicsRules physics_from_json(const json& j, const Experiment& base, const std::string& where) {
    if (!j.is_object() || !j.contains("materials") || !j.contains("actuation") ||
        !j.contains("simulation") || !j["simulation"].is_object())
        throw std::runtime_error(where + ": expected {materials, actuation, simulation}");
    json e = experiment_to_json(base);
    e["materials"] = j["materials"];
    e["actuation"] = j["actuation"];
    for (const char* key : {"bond_damping_ratio", "global_damping_ratio"}) {
        if (!j["simulation"].contains(key))
            throw std::runtime_error(where + ".simulation." + key + ": missing");
        e["simulation"][key] = j["simulation"][key];
    }
    const Experiment read = parse_experiment(e, where);
    if (read.materials.size() != base.materials.size())
        throw std::runtime_error(where + ".materials: " + std::to_string(read.materials.size()) +
                                 " materials, the run has " +
                                 std::to_string(base.materials.size()));
    return physics_of(read);
}

namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

void note(std::string& out, const std::string& what, double before, double after,
          const char* unit) {
    if (before == after) return;
    out += (out.empty() ? "" : ", ") + what + " " + number(before) + " -> " + number(after) +
           (*unit ? std::string(" ") + unit : std::string());
}

}  // namespace

std::string describe_physics_change(const Experiment& before, const PhysicsRules& after) {
    std::string out;
    for (std::size_t i = 0; i < before.materials.size() && i < after.materials.size(); ++i) {
        const auto& a = before.materials[i].physics;
        const auto& b = after.materials[i];
        const std::string n = "[" + before.materials[i].name + "]";
        note(out, "E" + n, a.youngs_modulus_pa, b.youngs_modulus_pa, "Pa");
        note(out, "density" + n, a.density_kg_m3, b.density_kg_m3, "kg/m^3");
        note(out, "nu" + n, a.poisson_ratio, b.poisson_ratio, "");
        note(out, "cte" + n, a.cte_per_c, b.cte_per_c, "1/C");
        note(out, "static friction" + n, a.static_friction, b.static_friction, "");
        note(out, "dynamic friction" + n, a.dynamic_friction, b.dynamic_friction, "");
        note(out, "contraction strain" + n, a.muscle.contraction_strain,
             b.muscle.contraction_strain, "");
        note(out, "activation time" + n, a.muscle.rise_s, b.muscle.rise_s, "s");
        note(out, "relaxation time" + n, a.muscle.decay_s, b.muscle.decay_s, "s");
        note(out, "pulse rate" + n, a.muscle.frequency_hz, b.muscle.frequency_hz, "Hz");
        note(out, "pulse width" + n, a.muscle.pulse_width_s, b.muscle.pulse_width_s, "s");
        note(out, "fatigue time" + n, a.muscle.fatigue_s, b.muscle.fatigue_s, "s");
        note(out, "recovery time" + n, a.muscle.recovery_s, b.muscle.recovery_s, "s");
        note(out, "fatigue floor" + n, a.muscle.fatigue_floor, b.muscle.fatigue_floor, "");
    }
    note(out, "amplitude", before.actuation.temperature_amplitude_c, after.temperature_amplitude_c,
         "C");
    note(out, "frequency", before.actuation.frequency_hz, after.frequency_hz, "Hz");
    note(out, "phase offset", before.actuation.phase_offset_rad, after.phase_offset_rad, "rad");
    note(out, "bond damping", before.simulation.bond_damping_ratio, after.bond_damping_ratio, "");
    note(out, "global damping", before.simulation.global_damping_ratio, after.global_damping_ratio,
         "");
    return out.empty() ? "physics unchanged" : "physics: " + out;
}

}  // namespace bhm::evo
