// The studio's Pareto plot (Analysis > Volume vs fitness, issue 44): its model against a hand-made
// population, and headless sessions in which a click on a point shows that body, in a live run
// and in a watched run directory (whose bodies come from the checkpoint).
#include <doctest/doctest.h>

#include <chrono>
#include <fstream>
#include <map>
#include <thread>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/session/pareto_model.hpp"
#include "app/gui/session/run_directory_watch.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "evo/run/population_csv.hpp"
#include "evo/run/run_output.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

PopulationMember member(std::int64_t id, double fitness, int voxels, bool valid = true) {
    PopulationMember m;
    m.id = id;
    m.fitness = fitness;
    m.voxels = voxels;
    m.valid = valid;
    return m;
}

//! A member of the snapshot's population that is not the champion and whose (volume, fitness)
//! no other member shares, so its point is its own to click; -1 when there is none.
std::int64_t lone_point(const EvolutionSnapshot& run) {
    std::map<std::pair<int, double>, int> count;
    for (const auto& e : pareto_entries(run))
        ++count[{e.voxels, e.fitness}];
    for (const auto& e : pareto_entries(run))
        if (!e.champion && count[{e.voxels, e.fitness}] == 1) return e.id;
    return -1;
}

}  // namespace

TEST_CASE("studio Pareto model: the members with a fitness, the volume front marked") {
    EvolutionSnapshot run;
    // (id: fitness, voxels) drawn by hand: 1 (5, 30) fittest, 2 (4, 20) smaller, 3 (4, 25)
    // beaten by 2, 4 (2, 10) smallest, 5 invalid, 6 diverged (negative fitness): not placed.
    run.population = {member(1, 5, 30), member(2, 4, 20),       member(3, 4, 25),
                      member(4, 2, 10), member(5, 9, 5, false), member(6, -1, 3)};
    run.has_champion = true;
    run.champion = run.population[0];
    auto entries = pareto_entries(run);
    REQUIRE(entries.size() == 4);
    std::vector<std::int64_t> ids;
    std::vector<bool> front;
    for (const auto& e : entries) {
        ids.push_back(e.id);
        front.push_back(e.on_front);
    }
    CHECK(ids == std::vector<std::int64_t>{1, 2, 3, 4});
    CHECK(front == std::vector<bool>{true, true, false, true});
    CHECK(entries[0].champion);
    CHECK_FALSE(entries[1].champion);
    CHECK_FALSE(entries[0].has_body);
    // Active voxels on x (always minimised): (id: fitness, active) 1 (5, 9), 2 (4, 2), 3 (4, 1),
    // 4 (2, 1): 3 now beats 2 (as fit, fewer active) and 4 (fitter, as few).
    const int active[] = {9, 2, 1, 1, 0, 0};
    for (std::size_t k = 0; k < run.population.size(); ++k)
        run.population[k].active_voxels = active[k];
    entries = pareto_entries(run, ParetoAxis::ActiveVoxels);
    front.clear();
    std::vector<int> xs;
    for (const auto& e : entries) {
        front.push_back(e.on_front);
        xs.push_back(e.voxels);
    }
    CHECK(xs == std::vector<int>{9, 2, 1, 1});
    CHECK(front == std::vector<bool>{true, false, true, false});
    // A run maximising volume: only the fittest (also the largest) is on the front.
    run.experiment.fitness.volume_objective = evo::VolumeObjective::Maximize;
    entries = pareto_entries(run);
    front.clear();
    for (const auto& e : entries)
        front.push_back(e.on_front);
    CHECK(front == std::vector<bool>{true, false, false, false});
}

TEST_CASE("studio Pareto plot: a click on a point shows that body, live and in a run directory") {
    const auto dir = testing::fresh_dir("pareto");
    auto e = testing::tiny_experiment();
    e.fitness.volume_objective = evo::VolumeObjective::Minimize;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1280, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                 {"wait_run": "finished"},
                                 {"click": "tab Volume vs fitness"}, {"frames": 3}])"));
    REQUIRE(studio.run.snapshot);
    const auto live = studio.run.snapshot;  // keeps the live population's bodies
    REQUIRE(studio.ui.widgets.count("pareto plot"));
    CHECK(studio.ui.widgets["pareto plot"].frame >= studio.ui.frame - 1);
    const std::int64_t id = lone_point(*live);
    REQUIRE(id >= 0);
    const std::string point = "pareto point #" + std::to_string(id);
    REQUIRE(studio.ui.widgets.count(point));
    testing::run_script_patiently(session,
                                  json::array({{{"click", point}}, {{"wait_simulation", true}}}));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->id == id);
    CHECK(studio.run.selected_id == id);
    // The x axis switched to active voxels and back: every point still drawn and recorded.
    testing::run_script_patiently(session, json::parse(R"([{"click": "pareto active voxels"},
                                                           {"frames": 3}])"));
    CHECK(studio.ui.widgets.at(point).frame >= studio.ui.frame - 1);
    testing::run_script_patiently(session, json::parse(R"([{"click": "pareto active voxels"},
                                                           {"frames": 3}])"));

    // The same run as a watched directory: population.csv's members, bodies from the checkpoint
    // on the first click, equal to the live run's.
    REQUIRE(fs::exists(dir / "run" / evo::kPopulationCsvFile));
    REQUIRE(open_run_directory(studio, (dir / "run").string()));
    REQUIRE(studio.run.snapshot);
    CHECK(studio.run.snapshot->population.size() == live->population.size());
    testing::run_script_patiently(
        session, json::parse(R"([{"click": "tab Volume vs fitness"}, {"frames": 3}])"));
    REQUIRE(studio.ui.widgets.count(point));
    CHECK(studio.ui.widgets[point].frame >= studio.ui.frame - 1);
    testing::run_script_patiently(session,
                                  json::array({{{"click", point}}, {{"wait_simulation", true}}}));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->id == id);
    const PopulationMember* watched = nullptr;
    for (const auto& m : studio.run.snapshot->population)
        if (m.id == id) watched = &m;
    const PopulationMember* original = nullptr;
    for (const auto& m : live->population)
        if (m.id == id) original = &m;
    REQUIRE(watched);
    REQUIRE(original);
    REQUIRE(watched->body);
    REQUIRE(original->body);
    CHECK(watched->body->cells == original->body->cells);
    CHECK(watched->voxels == original->voxels);
    CHECK(watched->fitness == original->fitness);
}

TEST_CASE("studio run directory: population.csv with fewer columns, or unreadable, still shows") {
    const auto dir = testing::fresh_dir("pareto-columns");
    const auto e = testing::tiny_experiment();
    evo::RunOutput out(dir.string());
    evo::RunState state;
    state.experiment = e;
    out.write_run_info(e, state);
    evo::HistoryRow row;
    out.write_fitness_csv({row});
    // Only the three columns the plot needs, written by hand: the rest take their defaults.
    std::ofstream(dir / evo::kPopulationCsvFile) << "id,fitness,voxels\n3,1.5,10\n4,2.5,12\n";
    RunDirectoryWatch watch;
    watch.open(dir.string());
    REQUIRE(watch.refresh());
    auto snap = watch.snapshot();
    REQUIRE(snap);
    REQUIRE(snap->population.size() == 2);
    CHECK(snap->population[0].id == 4);  // best fitness first
    CHECK(snap->population[0].voxels == 12);
    CHECK(snap->population[1].fitness == 1.5);
    CHECK(snap->population[1].valid);
    CHECK_FALSE(snap->population[1].exploits.checked);
    CHECK(snap->message.find("read-only view") != std::string::npos);
    // Without a needed column: the run is still shown, the message names the file and column.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // a distinct modification time
    std::ofstream(dir / evo::kPopulationCsvFile) << "id,fitness\n3,1.5\n";
    REQUIRE(watch.refresh());
    snap = watch.snapshot();
    REQUIRE(snap);
    CHECK(snap->population.empty());  // no champion file in this run
    CHECK(snap->message.find("population.csv") != std::string::npos);
    CHECK(snap->message.find("voxels") != std::string::npos);
    CHECK(watch.error().empty());
}
