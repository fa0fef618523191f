#pragma once
// What the muscle tests share (issue 43): a skeletal twitch and its material, the stimulus written
// out directly, the independent truth the engine's affine maps are checked against, and the
// refusal a bad body gets from Model::build.
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"

namespace bhm::engine::test {

// A skeletal muscle's twitch: 10 % contraction, 20 ms rise, 60 ms decay, 10 ms pulses at 1 Hz.
inline Muscle skeletal() {
    Muscle m;
    m.contraction_strain = 0.1;
    m.rise_s = 0.02;
    m.decay_s = 0.06;
    m.frequency_hz = 1.0;
    m.pulse_width_s = 0.01;
    return m;
}

// A muscle material of that twitch (or another) at Poisson's ratio nu, E and density the defaults.
inline Material muscle_material(const Muscle& m, double nu) {
    Material mat;
    mat.poisson_ratio = nu;
    mat.actuation_model = ActuationModel::Muscle;
    mat.muscle = m;
    return mat;
}

// u(t) of a pulse train, written out directly (not through the engine's affine maps).
inline bool pulse_on(const Muscle& m, double t) {
    if (t < 0.0) return false;
    if (m.train_on_s > 0.0 && m.train_off_s > 0.0) {
        const double in_burst = std::fmod(t, m.train_on_s + m.train_off_s);
        if (in_burst >= m.train_on_s) return false;
        t = in_burst;
    }
    return std::fmod(t, 1.0 / m.frequency_hz) < m.pulse_width_s;
}

// Model::build's message for a body it refuses; empty when it builds.
inline std::string build_refusal(const BodySpec& spec) {
    try {
        Model::build(spec);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return {};
}

}  // namespace bhm::engine::test
