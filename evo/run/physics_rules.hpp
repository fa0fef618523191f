#pragma once
// The physics a live run may be told to change (a calibration applied to it, docs/calibration.md):
// every material's values, the actuation's amplitude, frequency and phase offset, and the bond and
// global damping. Everything else of the experiment (the lattice, which materials exist and
// which are active, the boundary, the evaluation's times) stays, so every phenotype of the run
// develops as before and only its simulation changes. A physics change is a rule change
// (run_state.hpp's RuleChange::physics): from the generation it applies to, every member is
// simulated again and the fitness cache starts afresh (EvolutionRun::request_physics_change).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct PhysicsRules {
    std::vector<engine::Material> materials;  //!< (materials x 1), the experiment's order
    double frequency_hz = 0.0;
    double temperature_amplitude_c = 0.0;
    double phase_offset_rad = 0.0;
    double bond_damping_ratio = 0.0;
    double global_damping_ratio = 0.0;
    bool operator==(const PhysicsRules&) const = default;
};

//! The experiment's physics.
PhysicsRules physics_of(const Experiment& experiment);
//! The experiment with `physics` in place of its own. Throws std::invalid_argument when the
//! material count differs or a material would change between active and passive (the run's
//! phenotypes would then mean other bodies), and when the result does not validate
//! (validate_experiment's first problem, naming the field).
Experiment with_physics(const Experiment& experiment, const PhysicsRules& physics);

//! As the experiment file writes them: {"materials": [...], "actuation": {...},
//! "simulation": {"bond_damping_ratio", "global_damping_ratio"}}, each material whole (its
//! name, colour and library from `base`), so the entry reads like a part of the experiment file.
nlohmann::json physics_to_json(const PhysicsRules& physics, const Experiment& base);
//! Reads physics_to_json's object against `base` (the experiment it changes). Throws
//! std::runtime_error "WHERE: ..." naming the field.
PhysicsRules physics_from_json(const nlohmann::json& j, const Experiment& base,
                               const std::string& where);

//! One line saying what changed, e.g. "physics: E[muscle] 5e+06 -> 6e+06 Pa, amplitude 14.47 ->
//! 12 C" ("physics unchanged" when nothing did): the studio's rule-change note and status line.
std::string describe_physics_change(const Experiment& before, const PhysicsRules& after);

}  // namespace bhm::evo
