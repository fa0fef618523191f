// evolution.algorithm = "neat" end to end on a tiny workspace: the run improves, is the same for a
// seed whatever the thread count, and a stopped-then-resumed run equals its uninterrupted twin
// (NEAT state included); the experiment file's neat block is validated and round-trips.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "evo/experiment/experiment_io.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;

namespace {

Experiment neat_experiment() {
    auto e = test::tiny_experiment();
    e.evolution.algorithm = Algorithm::Neat;
    e.evolution.population = 10;
    e.evolution.neat.compatibility_threshold = 1.5;
    e.evolution.neat.target_species = 3;
    return e;
}

RunOptions options(int generations, int threads, const std::string& dir = "") {
    return test::run_options(generations, threads, dir);
}

fs::path fresh_dir(const std::string& name) {
    return test::fresh_dir("neat", name);
}

using test::without_wall;

std::string first_line(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

}  // namespace

TEST_CASE("a NEAT run speciates, keeps its best, improves and is the same for a seed") {
    const auto e = neat_experiment();
    EvolutionRun one(e, options(6, 1));
    one.run();
    const auto& history = one.state().history;
    REQUIRE(history.size() == 6);
    for (std::size_t g = 0; g < history.size(); ++g) {
        CHECK(history[g].species >= 1);
        if (g > 0) CHECK(history[g].best_fitness >= history[g - 1].best_fitness);  // elitism
    }
    CHECK(history.back().best_fitness > history.front().best_fitness);
    const auto& state = one.state();
    CHECK(static_cast<int>(state.population.size()) == e.evolution.population);
    std::size_t members = 0;
    for (const auto& s : state.neat.species)
        members += s.members.size();
    CHECK(members == state.population.size());
    for (const auto& m : state.population) {
        CHECK(m.genome.has_history());
        CHECK(genome_problem(m.genome, 1.0).empty());
    }
    CHECK(state.neat.next_innovation > 10);  // the minimal genomes' 10 genes, then new ones

    EvolutionRun two(e, options(6, 2));
    two.run();
    CHECK(without_wall(two.state().history) == without_wall(history));
    CHECK(two.state().neat == state.neat);
    CHECK(two.state().champion->individual.genome == state.champion->individual.genome);
}

TEST_CASE("a stopped and resumed NEAT run equals its uninterrupted twin") {
    const auto e = neat_experiment();
    const fs::path whole = fresh_dir("whole"), parts = fresh_dir("parts");
    EvolutionRun uninterrupted(e, options(5, 2, whole.string()));
    uninterrupted.run();
    auto resumed = test::stopped_then_resumed(e, parts.string(), 5, 2, 2);
    REQUIRE(resumed);
    CHECK(resumed->resume_warnings().empty());
    CHECK(resumed->state().generation == 2);
    CHECK(resumed->run() == StopReason::GenerationBudget);
    CHECK(without_wall(resumed->state().history) == without_wall(uninterrupted.state().history));
    CHECK(resumed->state().neat == uninterrupted.state().neat);
    CHECK(resumed->state().rng == uninterrupted.state().rng);
    CHECK(resumed->state().champion->individual.genome ==
          uninterrupted.state().champion->individual.genome);
    for (std::size_t i = 0; i < uninterrupted.state().population.size(); ++i)
        CHECK(resumed->state().population[i].genome == uninterrupted.state().population[i].genome);
    // fitness.csv names the species count of each generation.
    const std::string header = first_line(whole / "fitness.csv");
    CHECK(header.substr(header.size() - 8) == ",species");
    fs::remove_all(whole);
    fs::remove_all(parts);
}

TEST_CASE(
    "evolution.neat: defaults, validated ranges, round trip; AFPO files carry no neat block") {
    const auto afpo = test::tiny_experiment();
    CHECK_FALSE(experiment_to_json(afpo)["evolution"].contains("neat"));
    auto e = neat_experiment();
    const auto json = experiment_to_json(e);
    REQUIRE(json["evolution"].contains("neat"));
    CHECK(parse_experiment(json, "x.json") == e);

    auto bad = [&](auto change, const std::string& field) {
        auto x = e;
        change(x.evolution.neat);
        const auto problems = validate_experiment(x, "x.json");
        REQUIRE(problems.size() == 1);
        CHECK(problems[0].field == field);
    };
    bad([](NeatSettings& n) { n.c1 = -1; }, "evolution.neat.c1");
    bad([](NeatSettings& n) { n.c3 = 1e9; }, "evolution.neat.c3");
    bad([](NeatSettings& n) { n.compatibility_threshold = 0; },
        "evolution.neat.compatibility_threshold");
    bad([](NeatSettings& n) { n.survival_fraction = 0; }, "evolution.neat.survival_fraction");
    bad([](NeatSettings& n) { n.target_species = -1; }, "evolution.neat.target_species");
    bad([](NeatSettings& n) { n.elitism = -1; }, "evolution.neat.elitism");
    bad([](NeatSettings& n) { n.stagnation_generations = 0; },
        "evolution.neat.stagnation_generations");
    bad([](NeatSettings& n) { n.crossover_rate = 1.5; }, "evolution.neat.crossover_rate");

    auto text = json;
    text["evolution"]["neat"]["c4"] = 1;
    CHECK_THROWS_WITH_AS(parse_experiment(text, "x.json"), doctest::Contains("evolution.neat.c4"),
                         ValidationError);
}

TEST_CASE("a format 2 checkpoint of an AFPO run (before evolution.algorithm) still resumes") {
    const auto e = test::tiny_experiment();
    const fs::path whole = fresh_dir("afpo-whole"), old = fresh_dir("afpo-old");
    EvolutionRun uninterrupted(e, options(3, 1, whole.string()));
    uninterrupted.run();
    {
        EvolutionRun first(e, options(3, 1, old.string()));
        first.set_report_callback([&](auto r) {
            if (r->generation == 1) first.request_stop();
        });
        first.run();
    }
    // Rewrite both checkpoints as a build before this field wrote them: format 2 (a positional
    // cache), no algorithm, no species in the history rows.
    for (const char* name : {kCheckpointFile, kPreviousCheckpointFile}) {
        const fs::path path = old / name;
        std::vector<std::string> notes;
        auto payload = parse_checkpoint_text(bhm::test::read_file(path), notes);
        test::as_positional_cache(payload, 2);
        payload["experiment"]["evolution"].erase("algorithm");
        for (auto& row : payload["history"])
            row.erase("species");
        std::ofstream(path, std::ios::binary | std::ios::trunc) << checkpoint_text(payload);
    }
    auto resumed = EvolutionRun::resume(options(3, 1, old.string()));
    CHECK(resumed->resume_warnings().empty());
    CHECK(resumed->state().experiment.evolution.algorithm == Algorithm::Afpo);
    resumed->run();
    CHECK(without_wall(resumed->state().history) == without_wall(uninterrupted.state().history));
    CHECK(resumed->state().champion->individual.genome ==
          uninterrupted.state().champion->individual.genome);
    fs::remove_all(whole);
    fs::remove_all(old);
}

TEST_CASE("a change of fitness rules during a NEAT run restarts the species' records") {
    auto e = neat_experiment();
    EvolutionRun run(e, options(4, 1));
    run.set_report_callback([&](auto r) {
        if (r->generation == 1) {
            Fitness f = e.fitness;
            f.measure = FitnessMeasure::ComFinal3d;
            run.request_fitness_change(f);
        }
    });
    run.run();
    const auto& state = run.state();
    CHECK(state.experiment.fitness.measure == FitnessMeasure::ComFinal3d);
    CHECK(state.rules_version == 1);
    for (const auto& s : state.neat.species) {
        CHECK(s.last_improved >= 1);  // no record kept from the old measure
        double best = -1e300;
        for (int m : s.members)
            best = std::max(best, state.population[static_cast<std::size_t>(m)].report.fitness);
        CHECK(s.best_fitness >= best);
    }
}
