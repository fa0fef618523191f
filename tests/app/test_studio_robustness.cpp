// The studio's Robustness tab and controller reuse (issue 44), in headless sessions: a table
// picked in the tab equals `bhm robustness` for the same pairs cell for cell (and its CSV and
// heatmap exports are the CLI's bytes), a click on a cell shows that body driven by that
// controller, Cancel stops a table; a champion's controller exported from the studio is the
// run's controller file, and painted onto another body it replays as a plain evaluation of that
// pair.
#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/cli/commands.hpp"
#include "app/cli/png_encode.hpp"
#include "app/gui/actions/controller_actions.hpp"
#include "app/gui/actions/robustness_actions.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "engine/io/text_file.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/controller.hpp"
#include "support/captured_command.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The CLI suite's experiment: Table 1 materials on 3x2x2 held at x-, 0.02 s + 0.03 s.
evo::Experiment quick_experiment() {
    evo::Experiment e;
    e.name = "quick";
    e.workspace_size = {3, 2, 2};
    evo::MaterialEntry passive;
    passive.name = "passive";
    evo::MaterialEntry active = passive;
    active.name = "active";
    active.physics.cte_per_c = 0.01;
    e.materials = {passive, active};
    e.boundary.faces[static_cast<int>(evo::Face::XMin)] = evo::BoundaryKind::Fixed;
    e.actuation.frequency_hz = 25.0;
    e.simulation.settle_s = 0.02;
    e.simulation.evaluate_s = 0.03;
    e.simulation.record_fps = 100.0;
    e.fitness.measure = evo::FitnessMeasure::ComMax3d;
    e.evolution.threads = 2;
    return e;
}

// x = 0 passive (held), the rest active; `length` cells along x.
evo::Body bar(int length) {
    evo::Body b;
    b.size = {3, 2, 2};
    b.cells.assign(12, 0);
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < length; ++x)
                b.cells[b.index(x, y, z)] = x == 0 ? 1 : 2;
    return b;
}

std::string read_file(const fs::path& path) {
    return engine::read_text(path.string(), engine::kTextFileCap);
}

}  // namespace

TEST_CASE("studio robustness tab: the CLI's table, exports and a click on a cell shows the pair") {
    const auto dir = testing::fresh_dir("robustness-tab");
    const std::string experiment_path = (dir / "e.json").string();
    evo::save_experiment(experiment_path, quick_experiment());
    const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
    evo::save_body(a, bar(3));
    evo::save_body(b, bar(2));
    const std::string controllers = "uniform,wave,random:5";
    const auto cli = test::run_captured(
        app::cmd_robustness, {experiment_path, a, b, "--controllers", controllers, "--out",
                              (dir / "cli").string(), "--threads", "1"});
    INFO(cli.err);
    REQUIRE(cli.exit_code == 0);
    const auto cli_table = evo::parse_robustness_csv(read_file(dir / "cli" / "robustness.csv"));

    Studio studio;
    const evo::Experiment experiment = evo::load_experiment(experiment_path);
    studio.document.reset(experiment, experiment_path);
    studio.robustness.body_files = a + ", " + b;  // spaces around a name are dropped
    studio.robustness.controllers = controllers;
    HeadlessStudio session(studio, 1280, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "tab Robustness"},
                                 {"frames": 2}, {"click": "Run robustness"}])"));
    INFO(studio.ui.status);
    REQUIRE(testing::frames_until(session, [&] { return robustness_table(studio) != nullptr; }));
    const evo::RobustnessTable& table = *robustness_table(studio);
    REQUIRE(table.bodies == cli_table.bodies);
    REQUIRE(table.controllers == cli_table.controllers);
    REQUIRE(table.fitness.size() == 6);
    for (std::size_t k = 0; k < table.fitness.size(); ++k) {
        INFO("cell " << k);
        CHECK(table.fitness[k] == cli_table.fitness[k]);  // bit for bit
    }
    // Exports: the bytes bhm robustness wrote.
    REQUIRE(export_robustness_csv(studio, (dir / "studio" / "robustness.csv").string()));
    CHECK(read_file(dir / "studio" / "robustness.csv") ==
          read_file(dir / "cli" / "robustness.csv"));
    if (app::png_available()) {
        REQUIRE(export_robustness_png(studio, (dir / "studio" / "robustness.png").string()));
        CHECK(read_file(dir / "studio" / "robustness.png") ==
              read_file(dir / "cli" / "robustness.png"));
    }

    // The heatmap's cells are drawn and recorded; a click on (b.json, wave) shows that pair.
    testing::run_script_patiently(session, json::parse(R"([{"frames": 2}])"));
    REQUIRE(studio.ui.widgets.count("robustness cell 1,1"));
    CHECK(studio.ui.widgets["robustness cell 1,1"].frame >= studio.ui.frame - 1);
    testing::run_script_patiently(session, json::parse(R"([{"click": "robustness cell 1,1"},
                                                           {"wait_simulation": true}])"));
    REQUIRE(testing::frames_until(session, [&] {
        return studio.bodies.shown &&
               studio.bodies.shown->label.find("driven by wave") != std::string::npos;
    }));
    const evo::ControllerEntry wave{"wave", 1, ""};
    const evo::Body expected = evo::robustness_cell_body(experiment, bar(2), wave);
    const auto& shown = *studio.bodies.shown;
    REQUIRE(shown.framed_body);
    CHECK(shown.framed_body->cells == expected.cells);
    CHECK(shown.framed_body->phase == expected.phase);
    CHECK(shown.fitness == doctest::Approx(table.at(1, 1)).epsilon(1e-12));
    CHECK(studio.robustness.shown_body == 1);
    CHECK(studio.robustness.shown_controller == 1);

    // Bad input: one line naming the file, nothing started.
    studio.robustness.body_files = (dir / "missing.json").string();
    CHECK_FALSE(start_robustness(studio));
    CHECK(studio.ui.status_is_error);
    CHECK(studio.ui.status.find("missing.json") != std::string::npos);
    studio.robustness.body_files = a;
    studio.robustness.controllers = "uniform,sine";
    CHECK_FALSE(start_robustness(studio));
    CHECK(studio.ui.status.find("controllers: sine") != std::string::npos);
}

TEST_CASE("studio robustness runner: Cancel stops the cells and keeps no table") {
    RobustnessRunner runner;
    RobustnessRequest request;
    request.experiment = quick_experiment();
    request.experiment.simulation.evaluate_s = 1000.0;  // far longer than any test waits
    request.bodies = {bar(3), bar(2)};
    request.body_labels = {"a", "b"};
    request.controllers = {evo::resolve_robustness_controller("uniform", 3.0),
                           evo::resolve_robustness_controller("wave", 3.0)};
    request.threads = 2;
    REQUIRE(runner.start(request));
    CHECK_FALSE(runner.start(request));  // one table at a time
    runner.cancel();
    REQUIRE(
        bhm::test::wait_until([&] { return !runner.running(); },
                              [] { std::this_thread::sleep_for(std::chrono::milliseconds(1)); }));
    const auto state = runner.state();
    REQUIRE(state);
    CHECK(state->phase == RobustnessPhase::Cancelled);
    CHECK_FALSE(state->table);
    CHECK(state->total == 4);
}

TEST_CASE("studio controller: a champion's controller exported, then driving another body") {
    const auto dir = testing::fresh_dir("controller-reuse");
    auto e = testing::tiny_experiment();
    e.evolution.controller.mode = evo::ControllerMode::Coevolve;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1280, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                 {"wait_run": "finished"}, {"wait_simulation": true}])"));
    REQUIRE(studio.run.snapshot);
    REQUIRE(studio.run.snapshot->has_champion);
    const std::int64_t champion = studio.run.snapshot->champion.id;
    REQUIRE(testing::frames_until(session, [&] {
        return studio.bodies.shown && studio.bodies.shown->id == champion &&
               !studio.bodies.simulator.busy();
    }));
    // Exported: the controller file the run wrote beside its champion.
    const std::string path = (dir / "out" / "controller.json").string();
    REQUIRE(testing::frames_until(session, [&] { return export_shown_controller(studio, path); }));
    const json exported = json::parse(read_file(path));
    CHECK(exported == json::parse(read_file(dir / "run" / evo::kControllerFile)));
    CHECK(exported.at("format") == evo::kControllerFileFormat);
    const evo::Genome genome = evo::controller_from_json(exported, e.evolution.cppn.weight_range);

    // Onto another body: the tiny 2x2x1 body shown, then driven by the exported file.
    testing::request_tiny_body(studio, e, 99, "tiny body");
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true}])"));
    REQUIRE(testing::frames_until(
        session, [&] { return studio.bodies.shown && studio.bodies.shown->id == 99; }));
    const evo::Body plain = *studio.bodies.shown->framed_body;
    REQUIRE(drive_shown_body(studio, path));
    REQUIRE(testing::frames_until(session, [&] {
        return studio.bodies.shown && !studio.bodies.simulator.busy() &&
               studio.bodies.shown->label == "tiny body driven by " + path;
    }));
    evo::Body expected = plain;
    evo::paint_controller(genome, e.materials, expected);
    const auto& shown = *studio.bodies.shown;
    CHECK(shown.framed_body->cells == plain.cells);
    CHECK(shown.framed_body->phase == expected.phase);
    CHECK(shown.framed_body->amplitude == expected.amplitude);
    const evo::FitnessReport plain_run = evo::evaluate_body(e, expected);
    CHECK(shown.fitness ==
          doctest::Approx(evo::fitness_under(plain_run, e.fitness.measure)).epsilon(1e-12));
    // And out again: the body driven exports the controller it was driven by.
    const std::string again = (dir / "out" / "again.json").string();
    REQUIRE(export_shown_controller(studio, again));
    CHECK(json::parse(read_file(again)) == exported);
    // A controller that is not there: one line naming it, nothing requested.
    CHECK_FALSE(drive_shown_body(studio, (dir / "nothing.json").string()));
    CHECK(studio.ui.status.find("nothing.json") != std::string::npos);
}
