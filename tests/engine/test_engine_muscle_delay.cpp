// A muscle voxel's controller phase as a delay of its stimulus (issue 44; engine/muscle.hpp,
// docs/physics.md "Muscle actuation"). Truths: the activation ODE's closed form for one twitch,
// shifted by the delay; a link resting at the mean of its ends' activations; the same body with
// its actuation started later by the delay (today's undelayed path, a different code path); and
// bit-identity where the phase changes nothing (0, 2 pi, a phase in the same bin).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "engine/muscle.hpp"
#include "engine/poses.hpp"
#include "engine_test_bodies.hpp"
#include "muscle_test_support.hpp"
#include "free_body_checks.hpp"

using namespace bhm::engine;
using namespace bhm::engine::test;

namespace {

constexpr double kPi = std::numbers::pi;

// One twitch (a pulse of width w at t = 0), solved by hand; 0 before it.
double twitch(const Muscle& m, double t) {
    if (t <= 0.0) return 0.0;
    const double w = m.pulse_width_s;
    if (t <= w) return 1.0 - std::exp(-t / m.rise_s);
    return (1.0 - std::exp(-w / m.rise_s)) * std::exp(-(t - w) / m.decay_s);
}

// A free 2 x 1 x 1 muscle pair (nu 0, no gravity) with phases p0, p1: the largest
// |strain - truth(t)| of its x link over [0, t_end).
template <class Truth>
double worst_link_strain(const Muscle& m, double p0, double p1, double t_end, Truth truth) {
    BodySpec s = solid_box(2, 1, 1, muscle_material(m, 0.0));
    s.actuation.start_s = 0.0;
    s.phase_rad = {static_cast<float>(p0), static_cast<float>(p1)};
    auto model = Model::build(s);
    World w(model);
    double worst = 0.0;
    for (double t = 0.002; t < t_end; t += 0.002) {
        REQUIRE(w.advance_to(t));
        const double strain =
            (w.voxel_position_m(1)[0] - w.voxel_position_m(0)[0]) / s.voxel_size_m - 1.0;
        worst = std::max(worst, std::fabs(strain - truth(w.time_s())));
    }
    return worst;
}

// A 10 x 2 x 2 strip held at x = 0, its bottom layer muscle (fibres along x), nu 0.35 (the
// Poisson coupling on), gravity and the floor on, its actuation starting at start_s.
BodySpec held_strip(double start_s) {
    Muscle m = skeletal();
    m.frequency_hz = 4.0;
    Material passive;
    passive.youngs_modulus_pa = 1e6;
    passive.poisson_ratio = 0.35;
    Material muscle = muscle_material(m, 0.35);
    muscle.youngs_modulus_pa = 1e6;
    BodySpec s = solid_box(10, 2, 2, passive);
    s.materials.push_back(muscle);
    s.environment.floor = true;
    s.environment.gravity_m_s2 = -9.81;
    s.fixed.assign(s.material.size(), 0);
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 10; ++x) {
                if (z == 0) s.material[s.cell_index(x, y, z)] = 2;
                if (x == 0) s.fixed[s.cell_index(x, y, z)] = 1;
            }
    // Lift it off the floor by one voxel so that it hangs free.
    s.nz = 3;
    s.material.insert(s.material.begin(), 20, 0);
    s.fixed.insert(s.fixed.begin(), 20, 0);
    s.actuation.start_s = start_s;
    return s;
}

std::vector<float> positions_at(const BodySpec& s, double t) {
    World w(Model::build(s));
    REQUIRE(w.advance_to(t));
    VoxelPoses poses;
    w.read_poses(poses);
    return poses.position_m;
}

}  // namespace

TEST_CASE("muscle delay: a phase is the nearest of 16 delay bins of the stimulus period") {
    CHECK(muscle::delay_bin(0.0) == 0);
    CHECK(muscle::delay_bin(2.0 * kPi) == 0);
    CHECK(muscle::delay_bin(2.0 * kPi - 0.01) == 0);  // wraps: just under a turn is no delay
    CHECK(muscle::delay_bin(kPi / 2.0) == 4);
    CHECK(muscle::delay_bin(kPi / 2.0 + 0.19) == 4);  // within half a bin (pi / 16 = 0.196)
    CHECK(muscle::delay_bin(kPi / 2.0 + 0.2) == 5);
    CHECK(muscle::delay_bin(-kPi / 2.0) == 12);
    CHECK(muscle::delay_bin(kPi) == 8);
    CHECK(muscle::delay_bin(-kPi) == 8);
    CHECK(muscle::delay_bin(5.0 * kPi / 2.0) == 4);
    Muscle m = skeletal();
    m.frequency_hz = 50.0;
    CHECK(std::fabs(muscle::stimulus_period_s(m) - 0.02) < 1e-15);
    m.train_on_s = 0.3;
    m.train_off_s = 0.2;
    CHECK(std::fabs(muscle::stimulus_period_s(m) - 0.5) < 1e-15);  // a burst and its rest
    CHECK(std::fabs(muscle::bin_delay_s(m, 4) - 0.125) < 1e-15);
    m.stimulus = MuscleStimulus::Beating;  // beating has no schedule: one beat period
    CHECK(std::fabs(muscle::stimulus_period_s(m) - 0.02) < 1e-15);
}

TEST_CASE("muscle delay: a free link whose ends are delayed by tau0 follows -e a(t - tau0)") {
    const Muscle m = skeletal();  // 1 Hz: the first second is one twitch
    // Phase pi / 2: a quarter of the 1 s period, 0.25 s.
    const double tau0 = 0.25;
    const double worst = worst_link_strain(m, kPi / 2.0, kPi / 2.0, 0.8, [&](double t) {
        return -m.contraction_strain * twitch(m, t - tau0);
    });
    MESSAGE("largest |strain - (-e a(t - 0.25 s))| " << worst << " (e = 0.1)");
    // As the undelayed link of test_engine_muscle (measured 0.08 % of e there).
    CHECK(worst < 0.003 * m.contraction_strain);
    // Nothing moves before the delay: the link is exactly at rest.
    BodySpec s = solid_box(2, 1, 1, muscle_material(m, 0.0));
    s.actuation.start_s = 0.0;
    s.phase_rad = {static_cast<float>(kPi / 2.0), static_cast<float>(kPi / 2.0)};
    World w(Model::build(s));
    REQUIRE(w.advance_to(0.24));
    CHECK(std::fabs(w.voxel_position_m(1)[0] - w.voxel_position_m(0)[0] - s.voxel_size_m) < 1e-15);
    // The reported sizes are the voxel's own: 1 - e a(t - tau0) along the fibre, + 0 across.
    REQUIRE(w.advance_to(0.262));
    VoxelPoses poses;
    w.read_poses(poses);
    const double a = twitch(m, w.time_s() - tau0);
    CHECK(a > 0.1);
    CHECK(std::fabs(poses.size_m[0] / s.voxel_size_m - (1.0 - 0.1 * a)) < 1e-6);
    CHECK(std::fabs(poses.size_m[1] / s.voxel_size_m - 1.0) < 1e-6);
}

TEST_CASE("muscle delay: a link between two delays rests at the mean of its ends' activations") {
    const Muscle m = skeletal();
    // Phases 0 and pi: delays 0 and 0.5 s, two twitches half a second apart.
    const double worst = worst_link_strain(m, 0.0, kPi, 0.9, [&](double t) {
        return -m.contraction_strain * 0.5 * (twitch(m, t) + twitch(m, t - 0.5));
    });
    MESSAGE("largest |strain - (-e (a(t) + a(t - 0.5 s)) / 2)| " << worst);
    CHECK(worst < 0.003 * m.contraction_strain);
}

TEST_CASE("muscle delay: a body delayed by tau0 moves as the same body started tau0 later") {
    // Every muscle voxel at phase pi / 2 (a quarter of the 0.25 s period) against no phase and
    // the actuation started 1/16 s later: the second runs today's undelayed path, so this checks
    // the delayed coefficients every pass reads (links, Poisson, bond damping's rate, floor).
    BodySpec delayed = held_strip(0.1);
    delayed.phase_rad.assign(delayed.material.size(), static_cast<float>(kPi / 2.0));
    const BodySpec later = held_strip(0.1 + 0.0625);
    for (double t : {0.2, 0.45}) {
        const std::vector<float> a = positions_at(delayed, t), b = positions_at(later, t);
        REQUIRE(a.size() == b.size());
        // What the actuation moves: against the strip never actuated (sagging alike).
        const std::vector<float> rest = positions_at(held_strip(100.0), t);
        double worst = 0.0, motion = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            worst = std::max(worst, static_cast<double>(std::fabs(a[i] - b[i])));
            motion = std::max(motion, static_cast<double>(std::fabs(b[i] - rest[i])));
        }
        MESSAGE("t = " << t << " s: largest position difference " << worst << " m, motion "
                       << motion << " m");
        CHECK(motion > 1e-4);  // the muscle does bend the strip (L = 1 cm)
        // Float rounding of the rest lengths only (the same arithmetic in another order).
        CHECK(worst < 1e-6 * motion + 1e-9);
    }
}

TEST_CASE("muscle delay: phases that change no delay leave the body bit for bit as today") {
    const BodySpec today = held_strip(0.1);
    const std::vector<float> truth = positions_at(today, 0.3);
    auto with_phase = [&](float p) {
        BodySpec s = today;
        s.phase_rad.assign(s.material.size(), p);
        return positions_at(s, 0.3);
    };
    CHECK(with_phase(0.0f) == truth);
    CHECK(with_phase(static_cast<float>(2.0 * kPi)) == truth);
    CHECK(with_phase(0.1f) == truth);  // within bin 0
    // A phase on the passive voxels only drives nothing.
    BodySpec passive_phase = today;
    passive_phase.phase_rad.assign(today.material.size(), 0.0f);
    for (std::size_t c = 0; c < today.material.size(); ++c)
        if (today.material[c] == 1) passive_phase.phase_rad[c] = 2.0f;
    CHECK(positions_at(passive_phase, 0.3) == truth);
    // Delayed bodies: two phases in one bin are one body; a different bin is another.
    const std::vector<float> quarter = with_phase(static_cast<float>(kPi / 2.0));
    CHECK(with_phase(static_cast<float>(kPi / 2.0 + 0.1)) == quarter);
    CHECK(with_phase(static_cast<float>(-1.5 * kPi)) == quarter);
    CHECK(quarter != truth);
}

TEST_CASE("muscle delay: a free body of scattered delays keeps its momenta") {
    // The delayed coefficients act between voxels only: a free body (no gravity, floor, held
    // voxel or global damping) whose muscle voxels twitch at different times keeps zero
    // momentum, its centre of mass and zero spin.
    Muscle m = skeletal();
    m.frequency_hz = 10.0;
    BodySpec s = solid_box(4, 3, 2, muscle_material(m, 0.35));
    s.materials.push_back(s.materials[0]);
    s.materials[1].actuation_model = ActuationModel::Sine;  // a passive second material
    s.phase_rad.assign(s.material.size(), 0.0f);
    for (int c = 0; c < s.cell_count(); ++c) {
        if (c % 3 == 2) s.material[c] = 2;
        s.phase_rad[c] = static_cast<float>(0.7 * c);
    }
    s.actuation.start_s = 0.0;
    s.damping.global_ratio = 0.0;
    World w(Model::build(s));
    const double speed = check_free_body_keeps_momenta(w, 10, 0.02);
    MESSAGE("largest rms speed " << speed << " m/s");
    CHECK(speed > 1e-3);  // it does move inside
}
