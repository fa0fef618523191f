#pragma once
// Our engine's quasi-static answer at one load: the body with every active voxel held at a
// constant temperature change (frequency 0, phase +-pi/2: dT = A sin(+-pi/2) = +-A from t = 0,
// whatever the experiment's phases), gravity on, the floor off (the continuum model has no
// contact), and the global damping ratio at least 0.02; run in 0.05 s slices until the voxels move
// less than `tolerance` of their displacement over a slice. Damping does not change where a body
// comes to rest, only how soon; the ratio is a voxel's, so more of it overdamps a body's slow
// modes and it creeps to rest (docs/verify.md, "Our engine's answer").
//
// A muscle body's load is its activation a, 0 or 1 (ccx_deck.hpp): at 1 every muscle material is
// stimulated throughout from t = 0 (pulses as wide as their period), with a rise time of
// kHoldRiseS, so its activation 1 - exp(-t / kHoldRiseS) is 1 to double precision from 0.4 s on
// and within 3e-7 of it after the first three slices (the earliest a body may be found at rest);
// at 0 the actuation starts after the run. Only the evo side's copy of the spec changes: the
// engine and every experiment's own stimulus stay as they are.
#include <array>
#include <string>
#include <vector>

#include <atomic>

#include "engine/body_spec.hpp"
#include "engine/poses.hpp"

namespace bhm::evo {

struct QuasiStaticOptions {
    double global_damping_ratio = 0.02;  // docs/verify.md, "Our engine's answer"
    double tolerance = 1e-4;
    double max_time_s = 30.0;
    //! Raised: the run stops at the next slice with VerifyCancelled (verify_progress.hpp).
    const std::atomic<bool>* cancel = nullptr;
};

struct QuasiStaticResult {
    //! Per material cell in lattice order (as FemModel::voxel_cells): centre displacement (m).
    std::vector<std::array<double, 3>> displacement_m;
    //! The body where it came to rest, in the same order: each voxel's centre, orientation and
    //! edge lengths (what the studio draws under the FEM's ghost).
    engine::VoxelPoses shape;
    std::vector<std::array<double, 3>> rest_position_m;  //!< each voxel's centre at t = 0
    bool settled = false;
    std::string problem;  //!< "" or why there is no answer (diverged, did not settle)
    double simulated_s = 0.0;
    double cpu_s = 0.0;
};

//! The rise time of a muscle held at full activation (the static answer does not depend on it).
inline constexpr double kHoldRiseS = 0.01;

//! `temperature_c` is the uniform temperature change of every voxel (0 at rest); of a muscle
//! body (muscle_driven), the activation, 0 or 1 (else std::invalid_argument).
QuasiStaticResult engine_quasi_static(const engine::BodySpec& spec, double temperature_c,
                                      const QuasiStaticOptions& options = {});

}  // namespace bhm::evo
