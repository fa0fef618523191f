#pragma once
// Shared fixtures for the evo tests: tiny experiments built in code so every test is fast and says
// exactly what it depends on.
#include <array>
#include <string>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo::test {

//! Table 1 materials: 1 = passive (cte 0), 2 = active (cte 0.01).
inline Experiment tiny_experiment(std::array<int, 3> size = {4, 3, 3}) {
    Experiment e;
    e.name = "tiny";
    e.workspace_size = size;
    e.voxel_size_m = 0.01;
    MaterialEntry passive;
    passive.name = "passive";
    MaterialEntry active;
    active.name = "active";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(Face::XMin)] = BoundaryKind::Fixed;
    // Short and fast: 0.04 s simulated (a 1 cm voxel's stable step is ~1.4e-5 s) with a 25 Hz
    // drive so the window holds most of a period.
    e.actuation.frequency_hz = 25.0;
    e.simulation.settle_s = 0.01;
    e.simulation.evaluate_s = 0.03;
    e.simulation.record_fps = 200.0;
    e.fitness.measure = FitnessMeasure::ComMax3d;
    e.fitness.constraints.attached_to_fixed_face = true;
    e.fitness.constraints.min_active_voxels = 1;
    e.evolution.population = 6;
    e.evolution.generations = 3;
    e.evolution.max_neutral_retries = 200;
    e.evolution.seed = 7;
    return e;
}

}  // namespace bhm::evo::test
