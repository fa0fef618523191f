// Fitness measures against physics worked out by hand: free fall for the centre of mass, a
// thermal bimorph against a passive twin for the bend angle.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "engine/world.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/body_spec_of.hpp"
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

}  // namespace

TEST_CASE("centre-of-mass measures of a body in free fall") {
    auto e = test::tiny_experiment({2, 2, 2});
    e.boundary.faces = {};  // nothing held
    e.environment.floor = false;
    e.simulation.global_damping_ratio = 0.0;  // no drag toward rest: a pure free fall
    e.simulation.settle_s = 0.05;
    e.simulation.evaluate_s = 0.1;
    e.simulation.record_fps = 200.0;
    const auto r = evaluate_body(e, box({2, 2, 2}, 1), nullptr);
    REQUIRE_FALSE(r.diverged);
    // From t = ts to t = ts + T under g: d = g ts T + g T^2 / 2 = 0.0981 m = 9.81 voxels.
    const double g = 9.81, ts = 0.05, T = 0.1;
    const double expected_voxels = (g * ts * T + 0.5 * g * T * T) / e.voxel_size_m;
    const auto& m = r.measures;
    CHECK(m[static_cast<int>(FitnessMeasure::ComFinal3d)] ==
          bhm::test::relative(expected_voxels, 0.01));
    CHECK(m[static_cast<int>(FitnessMeasure::ComFinalYz)] ==
          bhm::test::relative(expected_voxels, 0.01));
    CHECK(m[static_cast<int>(FitnessMeasure::ComMax3d)] ==
          bhm::test::relative(expected_voxels, 0.01));
    CHECK(m[static_cast<int>(FitnessMeasure::ComMaxYz)] ==
          bhm::test::relative(expected_voxels, 0.01));
    CHECK(m[static_cast<int>(FitnessMeasure::BendAngleDeg)] < 0.5);  // a rigid fall does not bend
    CHECK(r.fitness == m[static_cast<int>(e.fitness.measure)]);
    CHECK(r.simulated_s >= 0.15 - 1e-9);
    CHECK(r.steps > 0);
}

TEST_CASE("an active/passive bimorph cantilever bends, its passive twin does not") {
    auto e = test::tiny_experiment({6, 1, 2});
    e.environment.gravity_m_s2 = 0.0;
    e.environment.floor = false;
    e.simulation.settle_s = 0.02;
    e.simulation.evaluate_s = 0.25;  // half a 2 Hz period: the expansion peaks at 0.125 s
    e.fitness.measure = FitnessMeasure::BendAngleDeg;
    Body bimorph = box({6, 1, 2}, 1);
    for (int x = 0; x < 6; ++x)
        bimorph.cells[bimorph.index(x, 0, 0)] = 2;  // bottom layer active
    const auto bent = evaluate_body(e, bimorph, nullptr);
    const auto still = evaluate_body(e, box({6, 1, 2}, 1), nullptr);
    REQUIRE_FALSE(bent.diverged);
    REQUIRE_FALSE(still.diverged);
    // Timoshenko's equal-layer bimorph: curvature 3 eps / (2 h), eps = 0.01 * 14.47, h = 2 cm,
    // gives ~37 degrees over 6 cm at full, static expansion; the dynamic voxel model reaches
    // part of it. The passive twin has nothing to drive it.
    CHECK(bent.fitness > 5.0);
    CHECK(bent.fitness < 60.0);
    CHECK(still.fitness < 0.5);
    CHECK(bent.measures[static_cast<int>(FitnessMeasure::ComMax3d)] >=
          bent.measures[static_cast<int>(FitnessMeasure::ComFinal3d)]);
}

TEST_CASE("a diverged report scores the documented finite worst value") {
    FitnessReport r;
    r.measures = {1, 2, 3, 4, 5};
    CHECK(fitness_under(r, FitnessMeasure::ComMaxYz) == 4);
    r.diverged = true;
    CHECK(fitness_under(r, FitnessMeasure::ComMaxYz) == kDivergedFitness);
    CHECK(std::isfinite(kDivergedFitness));
}

TEST_CASE("a raised cancel flag stops the evaluation") {
    const auto e = test::tiny_experiment({2, 1, 1});
    std::atomic<bool> cancel{true};
    CHECK_THROWS_AS(evaluate_body(e, box({2, 1, 1}, 1), &cancel), EvaluationCancelled);
}

TEST_CASE("a cancel raised between two samples stops the evaluation within a few steps") {
    // One sample per 1000 s: without the in-between checks this would simulate 1000 s (minutes
    // of wall time) before seeing the flag.
    auto e = test::tiny_experiment({2, 1, 1});
    e.simulation.settle_s = 0.0;
    e.simulation.evaluate_s = 1000.0;
    e.simulation.record_fps = 0.001;
    std::atomic<bool> cancel{false};
    const auto start = std::chrono::steady_clock::now();
    std::thread raiser([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        cancel.store(true);
    });
    CHECK_THROWS_AS(evaluate_body(e, box({2, 1, 1}, 1), &cancel), EvaluationCancelled);
    raiser.join();
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(waited < 10.0);  // generous for sanitizer builds; the full run takes minutes
}

TEST_CASE("a raised pause flag holds the evaluation until it is lowered, then it completes") {
    auto e = test::tiny_experiment({2, 1, 1});
    std::atomic<bool> pause{true}, cancel{false}, finished{false};
    FitnessReport paused_report;
    std::thread worker([&] {
        paused_report = evaluate_body(e, box({2, 1, 1}, 1), EvaluationControl{&cancel, &pause});
        finished.store(true);
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    CHECK_FALSE(finished.load());  // the whole evaluation takes a few milliseconds unpaused
    pause.store(false);
    worker.join();
    CHECK(finished.load());
    const auto plain = evaluate_body(e, box({2, 1, 1}, 1), nullptr);
    CHECK(paused_report.steps == plain.steps);
    CHECK(paused_report.fitness == plain.fitness);
}

TEST_CASE("a cancel ends a paused evaluation") {
    auto e = test::tiny_experiment({2, 1, 1});
    std::atomic<bool> pause{true}, cancel{false};
    std::thread raiser([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        cancel.store(true);
    });
    CHECK_THROWS_AS(evaluate_body(e, box({2, 1, 1}, 1), EvaluationControl{&cancel, &pause}),
                    EvaluationCancelled);
    raiser.join();
}
