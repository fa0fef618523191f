// Viewing a run directory: the files bhm evolve writes (through evo's own writers) become the
// snapshot the panels show, and are re-read only when they change.
#include <doctest/doctest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/gui/session/champion_history.hpp"
#include "app/gui/session/run_directory_watch.hpp"
#include "evo/run/run_output.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
namespace fs = std::filesystem;

namespace {

evo::ChampionRecord champion(const evo::Experiment& e, std::int64_t id, double fitness) {
    evo::ChampionRecord c;
    c.generation_found = 1;
    c.individual.id = id;
    c.individual.age = 2;
    c.individual.report.fitness = fitness;
    evo::Body body;
    body.size = e.workspace_size;
    body.cells.assign(static_cast<std::size_t>(body.cell_count()), 1);
    body.cells[1] = 2;
    c.individual.phenotype.body = body;
    c.individual.phenotype.voxels = body.cell_count();
    c.individual.phenotype.active_voxels = 1;
    return c;
}

evo::HistoryRow row(int g, double best, double median, int simulations) {
    evo::HistoryRow r;
    r.generation = g;
    r.simulations = simulations;
    r.evaluations = simulations;
    r.best_fitness = best;
    r.median_fitness = median;
    r.wall_s = 1.5 * (g + 1);
    return r;
}

}  // namespace

TEST_CASE("studio run directory: history, champion and rule changes are read and refreshed") {
    const auto dir = testing::fresh_dir("rundir");
    const auto e = testing::tiny_experiment();
    evo::RunOutput out(dir.string());
    evo::RunState state;
    state.experiment = e;
    state.seed = 5;
    out.write_run_info(e, state);
    std::vector<evo::HistoryRow> history = {row(0, 3.0, 1.0, 4), row(1, 4.5, 2.0, 3)};
    out.write_fitness_csv(history);
    out.write_champion(e, champion(e, 17, 4.5));

    RunDirectoryWatch watch;
    watch.open(dir.string());
    REQUIRE(watch.refresh());
    auto snap = watch.snapshot();
    REQUIRE(snap);
    CHECK(snap->experiment == e);
    REQUIRE(snap->history.size() == 2);
    CHECK(snap->history[1].best_fitness == 4.5);
    CHECK(snap->history[1].median_fitness == 2.0);
    CHECK(snap->history[1].evaluations == 7);  // simulations so far
    CHECK(snap->generation == 2);
    CHECK(snap->elapsed_s == doctest::Approx(3.0));
    REQUIRE(snap->has_champion);
    CHECK(snap->champion.id == 17);
    CHECK(snap->best_fitness == 4.5);
    REQUIRE(snap->champion.body);
    CHECK(snap->champion.body->cells[1] == 2);
    CHECK(snap->champion.body->size == e.workspace_size);

    // Nothing changed: no re-read.
    const int reloads = watch.reloads();
    CHECK_FALSE(watch.refresh());
    CHECK(watch.reloads() == reloads);

    // The run grows (a new generation and a change of rules): the view follows.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // a distinct modification time
    history.push_back(row(2, 6.0, 3.0, 2));
    out.write_fitness_csv(history);
    evo::Fitness changed = e.fitness;
    changed.measure = evo::FitnessMeasure::ComFinal3d;
    state.rule_changes.push_back({2, changed, std::nullopt, std::nullopt});
    out.write_run_info(e, state);
    REQUIRE(watch.refresh());
    snap = watch.snapshot();
    CHECK(snap->history.size() == 3);
    CHECK(snap->generation == 3);
    REQUIRE(snap->rule_changes.size() == 1);
    CHECK(snap->rule_changes[0].generation == 2);
    CHECK(snap->experiment.fitness.measure == evo::FitnessMeasure::ComFinal3d);
    CHECK(snap->has_champion);  // kept from the earlier read
}

TEST_CASE("studio run directory: a folder that is not a run, or a damaged file, is reported") {
    RunDirectoryWatch watch;
    CHECK_THROWS_WITH_AS(watch.open("/nonexistent/run"), "/nonexistent/run: no such run directory",
                         std::runtime_error);
    const auto empty = testing::fresh_dir("rundir-empty");
    CHECK_THROWS_AS(watch.open(empty.string()), std::runtime_error);

    const auto dir = testing::fresh_dir("rundir-damaged");
    evo::RunOutput out(dir.string());
    evo::RunState state;
    state.experiment = testing::tiny_experiment();
    out.write_run_info(state.experiment, state);
    std::ofstream(dir / "fitness.csv") << evo::kFitnessCsvHeader
                                     << "\n0,4,4,abc,1,0,3,0,1.0,0,0,0,0,0,11,11,0\n";
    // One bad row does not hide the run: the rows before it are shown and the row is named.
    std::ofstream(dir / "fitness.csv", std::ios::app) << "1,4,4,0.5,0.4,1,5,0,2.0,0,0,0,0,0,11,11,0\n";
    watch.open(dir.string());
    CHECK(watch.refresh());
    REQUIRE(watch.snapshot());
    CHECK(watch.snapshot()->history.empty());
    CHECK(watch.snapshot()->message.find("fitness.csv: row 2 is not numeric") !=
          std::string::npos);
    // A partial last row (a crash mid-append): the complete rows stay in view.
    std::ofstream(dir / "fitness.csv") << evo::kFitnessCsvHeader
                                     << "\n0,4,4,0.25,0.2,0,3,0,1.0,0,0,0,0,0,11,11,0\n1,4,4,0.5";
    std::filesystem::last_write_time(
        dir / "fitness.csv",
        std::filesystem::last_write_time(dir / "fitness.csv") + std::chrono::seconds(5));
    CHECK(watch.refresh());
    REQUIRE(watch.snapshot());
    REQUIRE(watch.snapshot()->history.size() == 1);
    CHECK(watch.snapshot()->history[0].best_fitness == 0.25);
    CHECK(watch.snapshot()->message.find("row 3 has 4 cells") != std::string::npos);
}

TEST_CASE("studio champion history: each report read through its one reader, a bad field named") {
    const auto dir = testing::fresh_dir("champion-history");
    const auto e = testing::tiny_experiment();
    evo::RunOutput out(dir.string());
    auto c = champion(e, 17, 4.5);
    c.individual.report.exploits.checked = true;
    c.individual.report.exploits.tentacle = true;
    out.write_champion(e, c);
    ChampionHistory history;
    REQUIRE(history.refresh(dir.string()));
    REQUIRE(history.entries().size() == 1);
    CHECK(history.entries()[0].exploits.tentacle);
    CHECK(history.error().empty());

    // A report whose field is damaged: the file and the field are named (issue 41: the studio
    // read report.exploits by hand, beside run_directory.cpp's own reading of the same file).
    const fs::path file = dir / "champions" / "gen-00002.json";
    auto j = nlohmann::json::parse(bhm::test::read_file(dir / "champion.json"));
    j["generation_found"] = 2;
    j["report"]["steps"] = "many";
    fs::remove(dir / "champions" / "gen-00001.json");  // the only file: its error stays shown
    std::ofstream(file) << j.dump(2);
    ChampionHistory again;
    again.refresh(dir.string());
    CHECK(again.error().find(file.string() + ":report.steps: expected an integer") !=
          std::string::npos);
    fs::remove_all(dir);
}
