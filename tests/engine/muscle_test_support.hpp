#pragma once
// What the muscle tests share (issue 43): the stimulus written out directly, the independent truth
// the engine's affine maps are checked against, and the refusal a bad body gets from Model::build.
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"

namespace bhm::engine::test {

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
