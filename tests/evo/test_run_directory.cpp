// The readers of a run directory (evo/run/run_directory.hpp) against what the run loop writes.
#include <doctest/doctest.h>

#include <fstream>

#include "evo/run/evolution_run.hpp"
#include "evo/run/run_directory.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;

TEST_CASE("run directory readers: run.json, champion.json and fitness.csv as the run wrote them") {
    const auto dir = bhm::test::scratch_dir("run-directory-read", false);
    const Experiment e = test::tiny_experiment();
    Fitness changed = e.fitness;
    changed.measure = FitnessMeasure::BendAngleDeg;
    {
        EvolutionRun run(e, test::run_options(2, 2, dir.string()));
        run.set_report_callback([&](auto r) {
            if (r->generation == 0) run.request_fitness_change(changed);
        });
        REQUIRE(run.run() == StopReason::GenerationBudget);
        const RunInfo info = read_run_info(dir.string());
        CHECK(info.started.fitness.measure == e.fitness.measure);
        REQUIRE(info.rule_changes.size() == 1);
        CHECK(info.rule_changes[0].generation == 1);
        CHECK(info.current().fitness.measure == FitnessMeasure::BendAngleDeg);

        const ChampionFile champion = read_champion_file(dir.string(), info.current());
        CHECK(champion.id == run.state().champion->individual.id);
        CHECK(champion.fitness == run.state().champion->individual.report.fitness);
        CHECK(champion.body.cells == run.state().champion->individual.phenotype.body.cells);

        const FitnessTable table = read_fitness_table(dir.string());
        CHECK(table.problem.empty());
        REQUIRE(table.rows.size() == run.state().history.size());
        CHECK(table.rows[1][table.column("best_fitness")] == run.state().history[1].best_fitness);
        CHECK_THROWS_WITH(table.column("no_such"), doctest::Contains("fitness.csv: no 'no_such'"));
    }
    // A row cut short by a crash (or being appended) ends the table; the rows before it stay.
    std::ofstream(dir / kFitnessCsvFile, std::ios::app) << "2,7,5,0.1";
    const FitnessTable cut = read_fitness_table(dir.string());
    CHECK(cut.rows.size() == 2);
    CHECK(cut.problem.find("fitness.csv: row 4 has 4 cells") != std::string::npos);

    // A champion of another experiment (its body does not fit) is refused, naming the file.
    Experiment other = e;
    other.workspace_size = {2, 2, 2};
    CHECK_THROWS_WITH(read_champion_file(dir.string(), other), doctest::Contains("champion.json"));
    std::filesystem::remove(dir / kRunInfoFile);
    CHECK_THROWS_WITH(read_run_info(dir.string()), doctest::Contains("run.json: "));
}
