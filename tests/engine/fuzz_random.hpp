#pragma once
// The envelope fuzzes' random numbers (test_engine_envelope*.cpp): SplitMix64, a fixed sequence
// on every platform (std:: distributions are not), so a seed names the same bodies everywhere;
// and the part of a random body both fuzzes draw alike.
#include <cstdint>
#include <cstdlib>

#include "engine/body_spec.hpp"
#include "engine/limits.hpp"
#include "engine_test_bodies.hpp"

namespace bhm::engine::test {

//! The rotary inertia scale of the fuzzes' "rotary inertia" cases: 1.5, or BHM_FUZZ_ROT_SCALE.
inline double fuzz_rotary_scale() {
    const char* scale = std::getenv("BHM_FUZZ_ROT_SCALE");
    return scale ? std::atof(scale) : 1.5;
}

struct Random {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

//! After the materials: the cells (a random fill of materials 1..materials, the first cell always
//! filled), half the bodies held at x-, random damping ratios and step fraction, the actuation
//! from t = 0. Draws in a fixed order, so a seed keeps naming the same bodies.
inline void draw_cells_damping_and_step(Random& r, BodySpec& s, int materials) {
    const double fill = 0.5 + 0.5 * r.uniform();
    s.material.assign(s.cell_count(), 0);
    for (std::uint8_t& c : s.material)
        c = r.uniform() < fill ? static_cast<std::uint8_t>(1 + r.below(materials)) : 0;
    s.material[0] = 1;
    if (r.below(2)) fix_x_min_layer(s);
    if (r.below(3) == 0) s.damping.bond_ratio = limits::kMaxDampingRatio * r.uniform();
    if (r.below(3) == 0) s.damping.global_ratio = r.uniform();
    if (r.below(3) == 0) s.damping.collision_ratio = 2.0 * r.uniform();
    s.dt_fraction = r.below(2) ? 0.3 + 0.7 * r.uniform() : r.below(2) ? 0.9 : 1.0;
    // BHM_FUZZ_DT_STRETCH (default 1) multiplies the drawn fraction, the same bodies drawn, to
    // probe the stability margin past 1 (issue 42: draws up to 1.3x a preset's dt_fraction).
    if (const char* stretch = std::getenv("BHM_FUZZ_DT_STRETCH"))
        s.dt_fraction *= std::atof(stretch);
    s.actuation.start_s = 0.0;
}

}  // namespace bhm::engine::test
