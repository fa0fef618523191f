// Volume as an objective (issue 44): the volume-vs-fitness front against hand-made sets, the
// volume in AFPO's domination and tie order, the experiment field and its refusal, and a run with
// the objective that resumes into its uninterrupted twin, population.csv included.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>

#include "evo/experiment/experiment_io.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/run/population_csv.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/search/afpo.hpp"
#include "evo/search/volume_front.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

TEST_CASE("volume front: the bodies no other beats on both fitness and volume") {
    // (fitness, voxels), drawn by hand on squared paper:
    //   0 (5, 30)  the fittest                                   front
    //   1 (4, 20)  less fit but smaller than 0                   front
    //   2 (4, 25)  as fit as 1 and larger: beaten by 1
    //   3 (2, 10)  the smallest                                  front
    //   4 (1, 10)  as small as 3, less fit: beaten by 3
    //   5 (3, 40)  beaten by 0 (fitter and smaller)
    //   6 (2, 10)  the same as 3: neither beats the other        front
    const std::vector<VolumePoint> points = {{5, 30}, {4, 20}, {4, 25}, {2, 10},
                                             {1, 10}, {3, 40}, {2, 10}};
    CHECK(volume_front(points, VolumeObjective::Minimize) ==
          std::vector<bool>{true, true, false, true, false, false, true});
    // Off plots the default trade-off (minimised volume).
    CHECK(volume_front(points, VolumeObjective::Off) ==
          volume_front(points, VolumeObjective::Minimize));
    // Maximised: 0 (5, 30) is beaten by nobody fitter; 5 (3, 40) is the largest; every other is
    // beaten by 0 (fitter and larger).
    CHECK(volume_front(points, VolumeObjective::Maximize) ==
          std::vector<bool>{true, false, false, false, false, true, false});
    CHECK(volume_front({}, VolumeObjective::Minimize).empty());
    CHECK(volume_front({{1.0, 7}}, VolumeObjective::Minimize) == std::vector<bool>{true});
}

TEST_CASE("AFPO with the volume objective: domination and the tie order") {
    // {fitness, age, active, id, second, voxels}
    const AfpoObjectives big{2.0, 1, 5, 0, 0.0, 30}, small{2.0, 1, 5, 1, 0.0, 20};
    AfpoOptions off, down, up;
    down.volume = VolumeObjective::Minimize;
    up.volume = VolumeObjective::Maximize;
    CHECK_FALSE(dominates(small, big, off));  // only the volume differs
    CHECK_FALSE(dominates(big, small, off));
    CHECK(dominates(small, big, down));
    CHECK_FALSE(dominates(big, small, down));
    CHECK(dominates(big, small, up));
    // A fitter but larger body no longer dominates a smaller one.
    const AfpoObjectives fit_big{3.0, 1, 5, 2, 0.0, 30};
    CHECK(dominates(fit_big, small, off));
    CHECK_FALSE(dominates(fit_big, small, down));
    CHECK(pareto_ranks({fit_big, small}, down) == std::vector<int>{0, 0});
    // Ties in the overflowing layer: volume in its direction before id; off, id alone decides.
    const std::vector<AfpoObjectives> tied = {{1, 2, 0, 4, 0.0, 30}, {1, 2, 0, 9, 0.0, 10}};
    CHECK(select_survivors(tied, 1, off) == std::vector<int>{0});
    CHECK(select_survivors(tied, 1, down) == std::vector<int>{1});
    CHECK(select_survivors(tied, 1, up) == std::vector<int>{0});
    // Off, the voxels are never looked at: the old bool overload selects the same.
    const std::vector<AfpoObjectives> pool = {{5, 3, 0, 0, 0, 9},  {4, 1, 0, 1, 0, 1},
                                              {3, 0, 0, 2, 0, 50}, {4, 3, 0, 3, 0, 2},
                                              {2, 2, 0, 4, 0, 7},  {1, 5, 0, 5, 0, 3}};
    CHECK(select_survivors(pool, 4, off) == select_survivors(pool, 4, false));
    CHECK(pareto_ranks(pool, off) == pareto_ranks(pool, false));
}

TEST_CASE("fitness.volume_objective: written, read back, refused by name when bad") {
    Experiment e = test::tiny_experiment();
    CHECK(experiment_to_json(e)["fitness"]["volume_objective"] == "off");
    e.fitness.volume_objective = VolumeObjective::Minimize;
    auto j = experiment_to_json(e);
    CHECK(j["fitness"]["volume_objective"] == "minimize");
    CHECK(parse_experiment(j, "v.json").fitness.volume_objective == VolumeObjective::Minimize);
    j["fitness"]["volume_objective"] = "maximize";
    CHECK(parse_experiment(j, "v.json").fitness.volume_objective == VolumeObjective::Maximize);
    j["fitness"].erase("volume_objective");  // files written before it: off
    CHECK(parse_experiment(j, "v.json").fitness.volume_objective == VolumeObjective::Off);
    j["fitness"]["volume_objective"] = "smaller";
    try {
        (void)parse_experiment(j, "v.json");
        FAIL("volume_objective \"smaller\" was accepted");
    } catch (const ValidationError& error) {
        REQUIRE(error.problems.size() == 1);
        CHECK(error.problems[0].field == "fitness.volume_objective");
        CHECK(error.problems[0].to_string().find('\n') == std::string::npos);
    }
}

TEST_CASE("a run minimising volume resumes into its uninterrupted twin, population.csv included") {
    Experiment e = test::tiny_experiment();
    e.fitness.volume_objective = VolumeObjective::Minimize;
    const fs::path whole = test::fresh_dir("volume", "whole"),
                   parts = test::fresh_dir("volume", "parts");
    auto twins = test::run_twins(e, whole.string(), parts.string(), 4, 2, 1);
    REQUIRE(twins.resumed);
    CHECK(twins.resumed->resume_warnings().empty());
    const auto& u = twins.whole->state();
    const auto& r = twins.resumed->state();
    CHECK(test::without_wall(r.history) == test::without_wall(u.history));
    CHECK(r.rng == u.rng);
    REQUIRE(r.population.size() == u.population.size());
    for (std::size_t i = 0; i < u.population.size(); ++i)
        CHECK(r.population[i].id == u.population[i].id);
    const std::string csv = bhm::test::read_file(whole / kPopulationCsvFile);
    CHECK(bhm::test::read_file(parts / kPopulationCsvFile) == csv);

    // population.csv is the final population, row by row, with each body's volume.
    const FitnessTable table = read_population_table(whole.string());
    CHECK(table.problem.empty());
    REQUIRE(table.rows.size() == u.population.size());
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
        const auto& row = table.rows[k];
        const auto& m = u.population[k];
        CHECK(row[table.column("generation")] == u.generation);
        CHECK(row[table.column("id")] == m.id);
        CHECK(row[table.column("fitness")] == m.report.fitness);
        CHECK(row[table.column("voxels")] == m.phenotype.voxels);
        CHECK(row[table.column("active_voxels")] == m.phenotype.active_voxels);
        CHECK(row[table.column("pareto_rank")] == u.pareto_rank[k]);
        CHECK(row[table.column("valid")] == (m.valid ? 1 : 0));
        CHECK(row[table.column("exploits_checked")] == (m.report.exploits.checked ? 1 : 0));
        CHECK(row[table.column("escaped")] == (m.report.exploits.escaped ? 1 : 0));
        CHECK(row[table.column("thin_share")] == m.report.exploits.thin_share);
        // Its volume is its body's filled cells, counted here again.
        int filled = 0;
        for (auto cell : m.phenotype.body.cells)
            filled += cell != 0;
        CHECK(m.phenotype.voxels == filled);
    }
    // The last selection's front (rank 0) holds members no other survivor dominates on fitness,
    // age and volume, checked by brute force.
    for (std::size_t i = 0; i < u.population.size(); ++i) {
        if (u.pareto_rank[i] != 0) continue;
        const auto& a = u.population[i];
        for (const auto& b : u.population) {
            const bool no_worse = b.report.fitness >= a.report.fitness && b.age <= a.age &&
                                  b.phenotype.voxels <= a.phenotype.voxels;
            const bool better = b.report.fitness > a.report.fitness || b.age < a.age ||
                                b.phenotype.voxels < a.phenotype.voxels;
            CHECK_FALSE((no_worse && better));
        }
    }
    twins = {};  // releases both runs' locks before their folders go
    fs::remove_all(whole);
    fs::remove_all(parts);
}
