// The behaviour descriptor (evo/evaluate/behaviour.hpp): a trajectory given by formula, worked out by hand;
// a free fall against g t^2 / 2 and against the fitness measure computed on its own; a bimorph
// whose tip swings while its passive twin's does not.
#include <doctest/doctest.h>

#include <cmath>

#include "evo/evaluate/behaviour.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo_test_support.hpp"
#include "support/relative_approx.hpp"

using namespace bhm::evo;

namespace {

Body box(std::array<int, 3> size, std::uint8_t material) {
    Body b;
    b.size = size;
    b.cells.assign(static_cast<std::size_t>(size[0] * size[1] * size[2]), material);
    return b;
}

//! Values of sample k (0-based): centre of mass x y z, tip x y z.
std::array<double, 6> sample(const std::vector<double>& d, int k) {
    std::array<double, 6> s{};
    for (std::size_t i = 0; i < 6; ++i)
        s[i] = d[static_cast<std::size_t>(k * kBehaviourPointValues) + i];
    return s;
}

}  // namespace

TEST_CASE("descriptor of a known trajectory: displacements from the settled sample at t_k") {
    static_assert(kBehaviourSamples == 4 && kBehaviourLength == 24);
    // settle 1 s, evaluate 4 s: the sample times are 2, 3, 4 and 5 s. Voxels of 1 cm.
    // COM x = 0.01 t m, tip y = 0.02 t^2 m, tip z = 0.03 m always (no motion).
    auto com = [](double t) { return std::array<double, 3>{0.01 * t, 0.0, 0.0}; };
    auto tip = [](double t) { return std::array<double, 3>{0.0, 0.02 * t * t, 0.03}; };
    SUBCASE("samples on the sample times") {
        BehaviourRecorder r(1.0, 4.0, 0.01);
        for (int i = 0; i <= 10; ++i)
            r.observe(0.5 * i, com(0.5 * i), tip(0.5 * i));
        const auto d = r.descriptor();
        REQUIRE(d.size() == 24u);
        // Reference at t = 1: COM x = t - 1 voxels; tip y = 2 (t^2 - 1) voxels.
        const double t[] = {2, 3, 4, 5};
        for (int k = 0; k < 4; ++k) {
            const auto s = sample(d, k);
            CHECK(s[0] == doctest::Approx(t[k] - 1.0).epsilon(1e-12));
            CHECK(s[1] == 0.0);
            CHECK(s[2] == 0.0);
            CHECK(s[3] == 0.0);
            CHECK(s[4] == doctest::Approx(2.0 * (t[k] * t[k] - 1.0)).epsilon(1e-12));
            CHECK(s[5] == 0.0);
        }
    }
    SUBCASE("samples off the sample times: the first at or after each is taken") {
        // Every 0.7 s: reference at 1.4, then 2.1 (for 2), 3.5 (for 3), 4.2 (for 4), 5.6 (for 5).
        BehaviourRecorder r(1.0, 4.0, 0.01);
        for (int i = 0; i <= 8; ++i)
            r.observe(0.7 * i, com(0.7 * i), tip(0.7 * i));
        const auto d = r.descriptor();
        REQUIRE(d.size() == 24u);
        const double taken[] = {2.1, 3.5, 4.2, 5.6};
        for (int k = 0; k < 4; ++k) {
            CHECK(sample(d, k)[0] == doctest::Approx(taken[k] - 1.4).epsilon(1e-9));
            CHECK(sample(d, k)[4] ==
                  doctest::Approx(2.0 * (taken[k] * taken[k] - 1.4 * 1.4)).epsilon(1e-9));
        }
    }
    SUBCASE("one sample standing for several sample times") {
        BehaviourRecorder r(1.0, 4.0, 0.01);
        r.observe(1.0, com(1.0), tip(1.0));
        r.observe(6.0, com(6.0), tip(6.0));
        const auto d = r.descriptor();
        REQUIRE(d.size() == 24u);
        for (int k = 0; k < 4; ++k)
            CHECK(sample(d, k)[0] == doctest::Approx(5.0));
    }
    SUBCASE("a trajectory that stops before the end has no descriptor") {
        BehaviourRecorder r(1.0, 4.0, 0.01);
        for (int i = 0; i <= 9; ++i)  // up to 4.5 s: the last sample time (5 s) is never reached
            r.observe(0.5 * i, com(0.5 * i), tip(0.5 * i));
        CHECK(r.descriptor().empty());
    }
}

TEST_CASE("a free fall's descriptor follows g t^2 / 2 and agrees with the fitness measure") {
    auto e = test::tiny_experiment({2, 2, 2});
    e.boundary.faces = {};  // nothing held
    e.environment.floor = false;
    e.simulation.global_damping_ratio = 0.0;
    e.simulation.settle_s = 0.05;
    e.simulation.evaluate_s = 0.1;
    e.simulation.record_fps = 200.0;  // a sample every 5 ms: on every t_k
    const auto r = evaluate_body(e, box({2, 2, 2}, 1), nullptr);
    REQUIRE_FALSE(r.diverged);
    REQUIRE(r.behaviour.size() == static_cast<std::size_t>(kBehaviourLength));
    const double g = 9.81, ts = 0.05;
    for (int k = 0; k < kBehaviourSamples; ++k) {
        CAPTURE(k);
        const double T = 0.1 * (k + 1) / kBehaviourSamples;
        const double fall_voxels = (g * ts * T + 0.5 * g * T * T) / e.voxel_size_m;
        const auto s = sample(r.behaviour, k);
        CHECK(std::abs(s[0]) < 1e-6);
        CHECK(std::abs(s[1]) < 1e-6);
        CHECK(-s[2] == bhm::test::relative(fall_voxels, 0.01));
        for (std::size_t i = 0; i < 3; ++i)  // a rigid fall: the tip falls with the body
            CHECK(s[3 + i] == doctest::Approx(s[i]).epsilon(1e-6));
    }
    // The last sample is the end of the simulation: its COM displacement is com_final_3d.
    const auto last = sample(r.behaviour, kBehaviourSamples - 1);
    const double norm = std::sqrt(last[0] * last[0] + last[1] * last[1] + last[2] * last[2]);
    CHECK(norm ==
          bhm::test::relative(r.measures[static_cast<int>(FitnessMeasure::ComFinal3d)], 1e-12));
}

TEST_CASE("a bending bimorph's tip swings, its passive twin stays where it settled") {
    auto e = test::tiny_experiment({6, 1, 2});
    e.environment.gravity_m_s2 = 0.0;
    e.environment.floor = false;
    e.simulation.settle_s = 0.02;
    e.simulation.evaluate_s = 0.25;
    Body bimorph = box({6, 1, 2}, 1);
    for (int x = 0; x < 6; ++x)
        bimorph.cells[bimorph.index(x, 0, 0)] = 2;  // bottom layer active
    const auto bent = evaluate_body(e, bimorph, nullptr);
    const auto still = evaluate_body(e, box({6, 1, 2}, 1), nullptr);
    REQUIRE(bent.behaviour.size() == static_cast<std::size_t>(kBehaviourLength));
    REQUIRE(still.behaviour.size() == static_cast<std::size_t>(kBehaviourLength));
    double bent_tip = 0.0, bent_com = 0.0;
    for (int k = 0; k < kBehaviourSamples; ++k) {
        const auto b = sample(bent.behaviour, k), s = sample(still.behaviour, k);
        bent_tip = std::max(bent_tip, std::abs(b[5]));
        bent_com = std::max(bent_com, std::abs(b[2]));
        for (double v : s)
            CHECK(std::abs(v) < 1e-3);
    }
    // An active bottom layer curls the beam upward; the free end moves most (a lever of 6).
    CHECK(bent_tip > 0.3);
    CHECK(bent_tip > 1.5 * bent_com);
}

TEST_CASE("a diverged simulation has no descriptor") {
    // A beam of 1 Pa jelly held at x- under 100 g: its links tear past a voxel's length.
    auto e = test::tiny_experiment({8, 1, 1});
    e.materials[0].physics.youngs_modulus_pa = 1.0;
    e.environment.gravity_m_s2 = -1000.0;
    e.environment.floor = false;
    const auto r = evaluate_body(e, box({8, 1, 1}, 1), nullptr);
    REQUIRE(r.diverged);
    CHECK(r.behaviour.empty());
}

TEST_CASE("descriptors survive checkpoints exactly, in reports and in the fitness cache") {
    FitnessReport r;
    for (int k = 0; k < kBehaviourLength; ++k)
        r.behaviour.push_back(1.0 / (k + 3.0) - 0.1);
    const auto back = report_from_json(report_to_json(r), "r");
    CHECK(back.behaviour == r.behaviour);

    auto json = report_to_json(r);
    json["behaviour"].erase(0);
    CHECK_THROWS_WITH(report_from_json(json, "r"), doctest::Contains("r.behaviour"));
    json.erase("behaviour");  // written before descriptors: none
    CHECK(report_from_json(json, "r").behaviour.empty());

    RunState state;
    state.experiment = test::tiny_experiment();
    state.seed = 7;
    state.rng = Rng(7).state();
    state.cache.insert(0x1234, r);
    FitnessReport diverged;
    diverged.diverged = true;
    state.cache.insert(0x5678, diverged);
    const auto loaded = run_state_from_json(run_state_to_json(state), "checkpoint");
    REQUIRE(loaded.cache.find(0x1234) != nullptr);
    CHECK(loaded.cache.find(0x1234)->behaviour == r.behaviour);
    CHECK(loaded.cache.find(0x5678)->behaviour.empty());
}
