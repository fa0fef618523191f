// A controller's phase as the muscle model's stimulus timing (issue 44): evolving a controller for
// the muscle catheter paints different delays on its muscle voxels, the delays reach the
// simulation, a muscle body without a controller keeps phase 0 whatever actuation.phase says,
// and the run's stopped-then-resumed twin equals it.
#include <doctest/doctest.h>

#include <set>
#include <string>

#include "engine/muscle.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"

using namespace bhm::evo;

namespace {

const std::string kRoot = BHM_SOURCE_DIR;

// muscle-catheter.json evolving a controller for its example body, on a short budget (the
// stimulus cycles at 2 Hz: a delay bin is 1/32 s).
Experiment muscle_fixed_body() {
    Experiment e = load_experiment(kRoot + "/assets/experiments/muscle-catheter.json");
    e.evolution.controller.mode = ControllerMode::FixedBody;
    e.evolution.controller.body = load_body(kRoot + "/assets/bodies/muscle-catheter.body.json");
    e.evolution.population = 4;
    e.evolution.seed = 3;
    e.simulation.settle_s = 0.05;
    e.simulation.evaluate_s = 0.25;
    return e;
}

// The distinct delay bins of a body's active muscle voxels.
std::set<int> muscle_bins(const bhm::engine::BodySpec& spec) {
    std::set<int> bins;
    for (std::size_t c = 0; c < spec.material.size(); ++c) {
        const int k = spec.material[c];
        if (k == 0) continue;
        const auto& m = spec.materials[static_cast<std::size_t>(k - 1)];
        if (m.actuation_model != bhm::engine::ActuationModel::Muscle || !is_active(m)) continue;
        bins.insert(bhm::engine::muscle::delay_bin(spec.phase_rad[c]));
    }
    return bins;
}

}  // namespace

TEST_CASE("muscle controller: a fixed-body run paints stimulus delays that change the motion") {
    const Experiment e = muscle_fixed_body();
    EvolutionRun run(e, test::run_options(2, 2));
    run.run();
    std::size_t most_bins = 0;
    for (const Individual& m : run.state().population)
        most_bins = std::max(most_bins, muscle_bins(make_body_spec(e, m.phenotype.body)).size());
    MESSAGE("most distinct delay bins in one member: " << most_bins);
    CHECK(most_bins >= 2);

    // The champion's delays are part of its fitness: the same body and amplitudes without them
    // (every phase 0, the stimulus as before issue 44) moves differently.
    const Individual& champion = run.state().champion->individual;
    REQUIRE(muscle_bins(make_body_spec(e, champion.phenotype.body)).size() >= 2);
    const FitnessReport again = evaluate_body(e, champion.phenotype.body);
    CHECK(again.fitness == champion.report.fitness);
    Body undelayed = champion.phenotype.body;
    undelayed.phase.assign(undelayed.phase.size(), 0.0f);
    const FitnessReport plain = evaluate_body(e, undelayed);
    MESSAGE("champion bend " << champion.report.fitness << " deg, without its delays "
                             << plain.fitness << " deg");
    CHECK(plain.fitness != champion.report.fitness);
}

TEST_CASE("muscle controller: without a controller a muscle voxel keeps phase 0") {
    // actuation.phase "random" and phase_offset_rad are the sine model's: a muscle body without
    // a controller keeps the stimulus timing it had before delays existed.
    Experiment e = load_experiment(kRoot + "/assets/experiments/muscle-catheter.json");
    e.actuation.phase = PhaseMode::Random;
    e.actuation.phase_offset_rad = 1.0;
    const Body framed =
        apply_frame_and_overrides(e, load_body(kRoot + "/assets/bodies/muscle-catheter.body.json"));
    const auto spec = make_body_spec(e, framed, 11);
    CHECK(muscle_bins(spec) == std::set<int>{0});
    for (std::size_t c = 0; c < spec.material.size(); ++c)
        if (spec.material[c] == 2) CHECK(spec.phase_rad[c] == 0.0f);
}

TEST_CASE("muscle controller: a fixed-body run resumes into its uninterrupted twin") {
    const Experiment e = muscle_fixed_body();
    const auto whole = test::fresh_dir("muscle-controller", "whole"),
               parts = test::fresh_dir("muscle-controller", "parts");
    test::check_twins_equal(test::run_twins(e, whole.string(), parts.string(), 3, 2, 1));
}
