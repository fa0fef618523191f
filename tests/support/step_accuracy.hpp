#pragma once
// The accuracy gate of the time step (tests/engine/test_engine_step_accuracy.cpp and
// tests/evo/test_step_accuracy_corpus.cpp): a body's trajectory at its default dt_fraction against
// a converged reference, the same body at dt_fraction 0.2.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"

namespace bhm::test {

//! The dt_fraction of the converged reference.
inline constexpr double kReferenceDtFraction = 0.2;

//! Every voxel's position at `samples` equally spaced times up to end_s (the first step at or
//! after each time), flattened [sample][voxel][xyz]; empty if the simulation diverged.
inline std::vector<double> sampled_positions(const engine::BodySpec& spec, double end_s,
                                             int samples) {
    engine::World world(engine::Model::build(spec));
    const int voxels = world.model().voxel_count();
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(samples) * voxels * 3);
    for (int k = 1; k <= samples; ++k) {
        if (!world.advance_to(end_s * k / samples)) return {};
        for (int v = 0; v < voxels; ++v) {
            const std::array<double, 3> p = world.voxel_position_m(v);
            out.insert(out.end(), p.begin(), p.end());
        }
    }
    return out;
}

//! How far a trajectory is from the reference: the RMS over voxels and samples of the distance
//! between the two, over the swing (the largest RMS displacement of the reference's voxels from
//! its first sample).
struct TrajectoryError {
    double rms_m = 0.0;
    double swing_m = 0.0;
    double relative() const { return rms_m / swing_m; }
};

inline TrajectoryError trajectory_error(const std::vector<double>& trial,
                                        const std::vector<double>& reference, int samples) {
    const std::size_t per_sample = reference.size() / samples;
    const double voxels = static_cast<double>(per_sample / 3);
    TrajectoryError e;
    double error2 = 0.0;
    for (int k = 0; k < samples; ++k) {
        double swing2 = 0.0;
        for (std::size_t j = 0; j < per_sample; ++j) {
            const std::size_t i = k * per_sample + j;
            const double moved = reference[i] - reference[j];
            const double off = trial[i] - reference[i];
            swing2 += moved * moved;
            error2 += off * off;
        }
        e.swing_m = std::max(e.swing_m, std::sqrt(swing2 / voxels));
    }
    e.rms_m = std::sqrt(error2 / (samples * voxels));
    return e;
}

//! The trajectory of `spec` as given against the same body at kReferenceDtFraction with the
//! explicit bond damping and unscaled rotary inertia; the error is infinite when either diverged.
inline TrajectoryError step_error(const engine::BodySpec& spec, double end_s, int samples) {
    engine::BodySpec reference_spec = spec;
    reference_spec.dt_fraction = kReferenceDtFraction;
    // The converged Kelvin-Voigt law: the explicit damping, uncapped at this step, whichever
    // integration of it `spec` asks for.
    reference_spec.damping.implicit_sweeps = 0;
    // And the voxels' own rotary inertia: a scaled one (the presets' 1.5, issue 42) is part of
    // the approximation the gate measures, not of the truth.
    reference_spec.rotary_inertia_scale = 1.0;
    const std::vector<double> reference = sampled_positions(reference_spec, end_s, samples);
    const std::vector<double> trial = sampled_positions(spec, end_s, samples);
    if (reference.empty() || trial.size() != reference.size()) return {INFINITY, 1.0};
    return trajectory_error(trial, reference, samples);
}

}  // namespace bhm::test
