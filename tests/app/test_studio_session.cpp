// Scripted headless sessions of the real studio UI (OSMesa): painter clicks, shortcuts, refused
// edits, screenshots against goldens, and evolution runs driven through the Run panel's buttons.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/gui/actions/key_bindings.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "render/image.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;

namespace {

evo::BoundaryKind face_kind(const Studio& s, evo::Face f) {
    return s.document.experiment().boundary.faces[static_cast<int>(f)];
}

}  // namespace

TEST_CASE("studio session: face clicks, undo / redo shortcuts, voxel painting, refused edits") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment({5, 4, 3}), "");
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"frames": 3}])"));
    CHECK(face_kind(studio, evo::Face::XMax) == evo::BoundaryKind::Free);

    run_script(session, json::parse(R"([{"click_face": "x+"}])"));
    CHECK(face_kind(studio, evo::Face::XMax) == evo::BoundaryKind::Fixed);
    CHECK(studio.document.undo_label() == "face x+ fixed");
    CHECK(studio.ui.status == "face x+ fixed");

    run_script(session, json::parse(R"([{"key": "ctrl+z"}])"));
    CHECK(face_kind(studio, evo::Face::XMax) == evo::BoundaryKind::Free);
    CHECK_FALSE(studio.document.can_undo());
    run_script(session, json::parse(R"([{"key": "ctrl+y"}])"));
    CHECK(face_kind(studio, evo::Face::XMax) == evo::BoundaryKind::Fixed);

    // The top-front-right cell, seen from the iso view, painted forbidden; then fixed.
    run_script(session, json::parse(R"([{"click_cell": [4, 0, 2], "brush": "forbidden"}])"));
    REQUIRE(studio.document.experiment().boundary.voxel_overrides.size() == 1);
    auto o = studio.document.experiment().boundary.voxel_overrides[0];
    CHECK(o.voxel == std::array<int, 3>{4, 0, 2});
    CHECK(o.kind == evo::OverrideKind::Empty);
    run_script(session, json::parse(R"([{"click_cell": [1, 0, 2], "brush": "fixed"}])"));
    REQUIRE(studio.document.experiment().boundary.voxel_overrides.size() == 2);
    o = studio.document.experiment().boundary.voxel_overrides[1];
    CHECK(o.voxel == std::array<int, 3>{1, 0, 2});
    CHECK(o.kind == evo::OverrideKind::Fixed);
    run_script(session, json::parse(R"([{"key": "ctrl+z"}])"));
    CHECK(studio.document.experiment().boundary.voxel_overrides.size() == 1);

    // An invalid value is refused with the validator's message and changes nothing.
    const auto before = studio.document.experiment();
    CHECK_THROWS_WITH_AS(
        run_script(session,
                   json::parse(R"([{"set": "materials[0].poisson_ratio", "value": 0.7}])")),
        doctest::Contains("materials[0].poisson_ratio: must be in [-0.9, 0.49]"), ScriptError);
    CHECK(studio.document.experiment() == before);
    CHECK(studio.ui.status_is_error);
    run_script(session, json::parse(R"([{"set": "simulation.evaluate_s", "value": 0.5}])"));
    CHECK(studio.document.experiment().simulation.evaluate_s == 0.5);

    // A step that cannot be done names the step.
    CHECK_THROWS_WITH_AS(run_script(session, json::parse(R"([{"frames": 1}, {"click": "Nope"}])")),
                         "step 2 (click): no widget named 'Nope' on screen", ScriptError);
    // ... by its kind, not by its first key in alphabetical order.
    CHECK_THROWS_WITH_AS(
        run_script(session, json::parse(R"([{"wait_run": "finished", "timeout_s": 0}])")),
        doctest::Contains("step 1 (wait_run): timed out after"), ScriptError);

    run_script(session, json::parse(R"([{"view": "iso"}, {"frames": 2}])"));
    testing::check_studio_golden("painter", session.capture(), session.font());
}

TEST_CASE("studio session: the help panel lists every shortcut (golden)") {
    Studio studio;
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"key": "f1"}, {"frames": 3}])"));
    CHECK(studio.ui.show_help);
    // Every shortcut is drawn whole inside the help window: no key, description or row cut off.
    const auto window = studio.ui.widgets.at("help window");
    for (const auto& binding : key_bindings())
        for (const char* prefix : {"help keys: ", "help: "}) {
            const std::string name = prefix + std::string(binding.keys);
            const auto it = studio.ui.widgets.find(name);
            REQUIRE_MESSAGE(it != studio.ui.widgets.end(), name);
            const auto& item = it->second;
            CHECK_MESSAGE(item.max.x <= window.max.x, name);
            CHECK_MESSAGE(item.max.y <= window.max.y, name);
            CHECK_MESSAGE(item.frame >= studio.ui.frame - 1, name);
        }
    testing::check_studio_golden("help", session.capture(), session.font());
    run_script(session, json::parse(R"([{"key": "f1"}])"));
    CHECK_FALSE(studio.ui.show_help);
}

TEST_CASE("studio session: Start runs two generations, the champion is selected and replayed") {
    const auto dir = testing::fresh_dir("session-run");
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([
        {"click": "Start"},
        {"wait_generations": 2},
        {"wait_run": "finished"},
        {"select": "champion"},
        {"wait_simulation": true},
        {"replay": {"time_s": 0.3, "playing": false}}])"));
    const auto run = studio.run.evolution.snapshot();
    REQUIRE(run);
    CHECK(run->phase == RunPhase::Finished);
    CHECK(run->generation == 2);
    CHECK(run->history.size() == 2);
    CHECK(run->population.size() == 4);
    REQUIRE(run->has_champion);
    CHECK(run->champion.fitness >= 0.0);
    // The same files as bhm evolve.
    for (const char* name : {"run.json", "fitness.csv", "champion.json", "checkpoint.json"})
        CHECK_MESSAGE(std::filesystem::exists(dir / "run" / name), name);
    // The champion was simulated again for the view, with the same fitness evolution measured.
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->id == run->champion.id);
    CHECK(studio.bodies.shown->fitness == doctest::Approx(run->champion.fitness).epsilon(1e-9));
    CHECK(studio.bodies.shown->label.find("champion #" + std::to_string(run->champion.id)) == 0);
    CHECK(studio.view.mode == ViewMode::Simulation);
    CHECK(studio.clock.time_s == doctest::Approx(0.3));
    CHECK(studio.clock.duration_s == doctest::Approx(0.4).epsilon(0.02));

    // Exports from the Export tab: the champion as VXA and body JSON, the replay as frames, and
    // the 3D view at a size of its own.
    studio.exports.champion_vxa_path = (dir / "champion.vxa").string();
    studio.exports.champion_json_path = (dir / "champion-body.json").string();
    studio.exports.frames_folder = (dir / "frames").string();
    studio.exports.frames_width = 160;
    studio.exports.frames_height = 100;
    studio.exports.frames_fps = 10.0;
    const auto view_png = (dir / "view.png").string();
    run_script(session, json::array({{{"click", "tab Export"}},
                                     {{"click", "Save VXA"}},
                                     {{"click", "Save body JSON"}},
                                     {{"click", "Write frames"}},
                                     {{"frames", 8}},
                                     {{"export_view", view_png}, {"size", {320, 200}}}}));
    CHECK(evo::load_body(studio.exports.champion_json_path) == *studio.bodies.shown->framed_body);
    std::ifstream vxa(studio.exports.champion_vxa_path);
    const std::string vxa_text((std::istreambuf_iterator<char>(vxa)),
                               std::istreambuf_iterator<char>());
    CHECK(vxa_text.find("<VXA") != std::string::npos);
    for (int i = 0; i <= 4; ++i) {  // 0.4 s at 10 frames/s: t = 0, 0.1, ..., 0.4
        const auto frame = dir / "frames" / ("frame_0000" + std::to_string(i) + ".png");
        REQUIRE_MESSAGE(std::filesystem::exists(frame), frame.string());
    }
    CHECK_FALSE(std::filesystem::exists(dir / "frames" / "frame_00005.png"));
    const auto frame = render::read_png((dir / "frames" / "frame_00004.png").string());
    CHECK(frame.width == 160);
    CHECK(frame.height == 100);
    const auto view = render::read_png(view_png);
    CHECK(view.width == 320);
    CHECK(view.height == 200);

    // The folder the run wrote, opened as a run directory, shows the same history and champion.
    REQUIRE(open_run_directory(studio, (dir / "run").string()));
    session.frame();
    REQUIRE(studio.run.snapshot);
    CHECK(studio.run.snapshot->history.size() == 2);
    CHECK(studio.run.snapshot->champion.id == run->champion.id);
    CHECK(studio.run.snapshot->champion.fitness == run->champion.fitness);
    CHECK(*studio.run.snapshot->champion.body == *run->champion.body);
    CHECK(studio.run.snapshot->history.back().best_fitness == run->history.back().best_fitness);
}

TEST_CASE("studio session: pause, change the fitness measure, resume, stop and resume the folder") {
    const auto dir = testing::fresh_dir("session-rules");
    Studio studio;
    auto e = testing::tiny_experiment();
    e.evolution.generations = 8;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([
        {"click": "Start"},
        {"wait_generations": 1},
        {"click": "Pause"},
        {"wait_run": "paused"},
        {"set": "fitness.measure", "value": "com_final_3d"},
        {"click": "Resume"}])"));
    // Generations are fast here: the pause may land a generation or two later than asked, so
    // wait for the first generation scored under the new rules, counted from where it paused.
    const int paused_at = studio.run.evolution.snapshot()->generation;
    CHECK(studio.ui.status == "evolution resumed");
    CHECK(paused_at < 6);  // leaves room to stop before the budget of 8
    testing::run_script_patiently(session, json::array({{{"wait_generations", paused_at + 1}},
                                                        {{"click", "Stop"}},
                                                        {{"wait_run", "stopped"}}}));
    auto run = studio.run.evolution.snapshot();
    REQUIRE(run);
    CHECK(run->experiment.fitness.measure == evo::FitnessMeasure::ComFinal3d);
    REQUIRE(run->rule_changes.size() == 1);
    CHECK(run->rule_changes[0].generation <= paused_at);
    CHECK(run->rule_changes[0].description.find("com_final_3d") != std::string::npos);
    const int stopped_at = run->generation;
    CHECK(stopped_at > paused_at);
    // A stopped run is going nowhere: its last estimate stays in the snapshot, the Run panel's
    // figures have no ETA.
    CHECK(run->eta_s > 0.0);
    CHECK(live_figures(*run, studio.run.evolution.progress(), studio.run.evolution.phase()).eta_s <
          0.0);
    session.frame();  // the status line says how the run ended, not the last button's word
    CHECK_MESSAGE(studio.ui.status == run->message, studio.ui.status);
    // One plot per measure: degrees and voxels never share a line or an axis.
    const auto series = split_by_measure(*run);
    REQUIRE(series.size() == 2);
    CHECK(series[0].measure == evo::FitnessMeasure::BendAngleDeg);
    CHECK(series[1].measure == evo::FitnessMeasure::ComFinal3d);
    CHECK(series[0].records.back().generation < series[1].records.front().generation);
    CHECK(series[0].records.size() + series[1].records.size() == run->history.size());
    session.frame();
    // Too low for two plots stacked at their minimum height: a tab each, the newest measure's
    // shown (tests/app/test_studio_layout.cpp).
    for (const char* tab : {"fitness tab bend_angle_deg", "fitness tab com_final_3d"})
        CHECK_MESSAGE(studio.ui.widgets.at(tab).frame >= studio.ui.frame - 1, tab);
    CHECK(studio.ui.widgets.at("fitness plot com_final_3d").frame >= studio.ui.frame - 1);

    // Resume the folder from its checkpoint: it finishes the budget of 8 generations, keeping
    // the history and the rule change.
    REQUIRE(resume_run_directory(studio, (dir / "run").string()));
    testing::run_script_patiently(session, json::parse(R"([{"wait_run": "finished"}])"));
    session.frame();
    CHECK_MESSAGE(studio.ui.status == "finished: generation budget reached", studio.ui.status);
    run = studio.run.evolution.snapshot();
    CHECK(run->generation == 8);
    CHECK(run->history.size() == 8);
    CHECK(run->rule_changes.size() == 1);
    CHECK(run->experiment.fitness.measure == evo::FitnessMeasure::ComFinal3d);
}

TEST_CASE("studio session: a simulated body replays at t = 5 s with the settle phase first") {
    auto e = testing::tiny_experiment({2, 2, 1});
    e.simulation.settle_s = 0.2;
    e.simulation.evaluate_s = 5.0;
    Studio studio;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1024, 700);
    testing::request_tiny_body(studio, e, 3, "test body");
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                 {"replay": {"time_s": 5.0, "playing": false}},
                                 {"frames": 2}])"));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.clock.time_s == 5.0);
    CHECK(studio.clock.duration_s == doctest::Approx(5.2).epsilon(0.01));
    const auto& replay = studio.bodies.shown->replay;
    CHECK(replay.settle_s == 0.2);
    const int frame = frame_index_at(replay, 5.0);
    CHECK(std::abs(replay.frames[static_cast<std::size_t>(frame)].time_s - 5.0) < 1.0 / 30.0);
    CHECK(std::abs(frame - 150) <= 1);  // 30 frames per second
    // Playing on from 5 s advances with the UI's frame time.
    run_script(session, json::parse(R"([{"key": "space"}, {"frames": 6}])"));
    CHECK(studio.clock.playing);
    CHECK(studio.clock.time_s > 5.0);
}

TEST_CASE("studio session: the experiment editor picks NEAT, Start runs it and shows its species") {
    const auto dir = testing::fresh_dir("session-neat");
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 1400);
    run_script(session, json::parse(R"([
        {"click": "header Evolution"}, {"frames": 2},
        {"click": "Algorithm"}, {"frames": 2},
        {"click": "algorithm neat"}, {"frames": 2}])"));
    CHECK(studio.document.experiment().evolution.algorithm == evo::Algorithm::Neat);
    CHECK(studio.document.undo_label() == "set evolution.algorithm");
    testing::run_script_patiently(session, json::parse(R"([
        {"set": "evolution.neat.target_species", "value": 2},
        {"click": "Start"},
        {"wait_generations": 2},
        {"wait_run": "finished"},
        {"frames": 2}])"));
    const auto run = studio.run.evolution.snapshot();
    REQUIRE(run);
    CHECK(run->experiment.evolution.algorithm == evo::Algorithm::Neat);
    CHECK(run->experiment.evolution.neat.target_species == 2);
    CHECK(run->generation == 2);
    CHECK(run->species >= 1);
    for (const auto& m : run->population)
        CHECK(m.species >= 1);  // the Population panel's species column
    std::ifstream csv(dir / "run" / "fitness.csv");
    std::string header;
    std::getline(csv, header);
    CHECK(header.substr(header.size() - 8) == ",species");
}

TEST_CASE("studio session: opening a file with several errors names every one in the status") {
    const auto dir = testing::fresh_dir("session-problems");
    json doc = evo::experiment_to_json(testing::tiny_experiment());
    doc["materials"][0]["poisson_ratio"] = 0.7;
    doc["evolution"]["generations"] = -3;
    const auto path = (dir / "two-errors.json").string();
    std::ofstream(path) << doc.dump(2);
    Studio studio;
    HeadlessStudio session(studio, 800, 500);
    CHECK_THROWS_AS(run_script(session, json::array({{{"load", path}}})), ScriptError);
    CHECK(studio.ui.status_is_error);
    CHECK_MESSAGE(studio.ui.status.find("materials[0].poisson_ratio") != std::string::npos,
                  studio.ui.status);
    CHECK_MESSAGE(studio.ui.status.find("evolution.generations") != std::string::npos,
                  studio.ui.status);
    CHECK(studio.ui.edit_problems.size() == 2);
}

TEST_CASE("studio session: F12 numbers its screenshots in the data folder and names them whole") {
    namespace fs = std::filesystem;
    const auto dir = fs::absolute(testing::fresh_dir("session-f12"));
    const char* old_xdg = std::getenv("XDG_DATA_HOME");
    const std::string saved = old_xdg ? old_xdg : "";
    setenv("XDG_DATA_HOME", dir.c_str(), 1);
    {
        Studio studio;
        studio.document.reset(testing::tiny_experiment(), "");
        studio.exports.screenshot_width = 64;
        studio.exports.screenshot_height = 48;
        HeadlessStudio session(studio, 800, 500);
        run_script(session, json::parse(R"([{"key": "f12"}])"));
        const auto first = dir / "bhm-studio" / "screenshots" / "bhm-view-001.png";
        const auto second = dir / "bhm-studio" / "screenshots" / "bhm-view-002.png";
        CHECK(fs::exists(first));
        CHECK_MESSAGE(studio.ui.status.find(first.string()) != std::string::npos, studio.ui.status);
        run_script(session, json::parse(R"([{"key": "f12"}])"));
        CHECK(fs::exists(first));  // kept, not overwritten
        CHECK(fs::exists(second));
        CHECK_MESSAGE(studio.ui.status.find(second.string()) != std::string::npos,
                      studio.ui.status);
        CHECK(render::read_png(second.string()).width == 64);
    }
    if (old_xdg)
        setenv("XDG_DATA_HOME", saved.c_str(), 1);
    else
        unsetenv("XDG_DATA_HOME");
}

TEST_CASE("studio session: picking HyperNEAT shows NEAT's and its substrate's fields") {
    // Issue 44: the experiment editor showed NEAT's fields for "neat" only, so a HyperNEAT
    // experiment (NEAT evolving the substrate's CPPN) could not set its species or its substrate.
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1024, 1400);
    auto shown = [&](const char* widget) {
        const auto it = studio.ui.widgets.find(widget);
        return it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame;
    };
    run_script(session, json::parse(R"([{"click": "header Evolution"}, {"frames": 2}])"));
    CHECK_FALSE(shown("evolution.hyperneat.radius"));
    run_script(session, json::parse(R"([
        {"click": "Algorithm"}, {"frames": 2},
        {"click": "algorithm hyperneat"}, {"frames": 2}])"));
    CHECK(studio.document.experiment().evolution.algorithm == evo::Algorithm::HyperNeat);
    CHECK(shown("evolution.hyperneat.radius"));
    CHECK(shown("evolution.neat.target_species"));
}
