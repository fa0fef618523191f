// Scripted headless sessions of the Run panel's states that must never be stale or silent: a
// resume that fails, the messages and labels around a change of rules or of run.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/redraw_gate.hpp"
#include "app/gui/shell/script.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/evolution_run.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

//! A finished run of `generations` generations in dir, written by evo (not by the studio).
void write_run(const fs::path& dir, const evo::Experiment& e) {
    evo::RunOptions options;
    options.out_dir = dir.string();
    evo::EvolutionRun run(e, options);
    run.run();
}

bool drawn_now(const Studio& s, const std::string& widget) {
    const auto it = s.ui.widgets.find(widget);
    return it != s.ui.widgets.end() && it->second.frame == s.ui.frame;
}

}  // namespace

TEST_CASE("studio run states: a resume with no usable checkpoint fails in red and offers a start") {
    const auto dir = fs::absolute(testing::fresh_dir("states-damaged"));
    auto e = testing::tiny_experiment();
    e.name = "damaged";
    e.evolution.generations = 1;
    write_run(dir / "run", e);
    for (const char* name : {evo::kCheckpointFile, evo::kPreviousCheckpointFile})
        std::ofstream(dir / "run" / name) << "{ damaged";

    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1024, 700);
    REQUIRE(resume_run_directory(studio, (dir / "run").string()));
    testing::run_script_patiently(session,
                                  json::parse(R"([{"wait_run": "failed"}, {"frames": 2}])"));
    // The Run panel says why, in the CLI's words (it said "loading the checkpoint" for ever).
    CHECK(drawn_now(studio, "run failure"));
    const auto run = studio.run.evolution.snapshot();
    REQUIRE(run);
    CHECK_MESSAGE(run->message.find("no usable checkpoint") != std::string::npos, run->message);
    CHECK(studio.ui.status_is_error);
    CHECK_MESSAGE(studio.ui.status.find("no usable checkpoint") != std::string::npos,
                  studio.ui.status);

    // The fallback: the run's own experiment from generation 0 in a new folder.
    const auto runs_root = dir / "data";
    setenv("XDG_DATA_HOME", runs_root.c_str(), 1);
    REQUIRE(drawn_now(studio, "Start again from generation 0"));
    run_script(session, json::parse(R"([{"click": "Start again from generation 0"},
                                        {"frames": 2}])"));
    INFO("status: " << studio.ui.status);
    // Started: a one-generation run can already be finished two frames later on a loaded
    // machine, where llvmpipe's frames are slow beside the worker.
    const RunPhase started = studio.run.evolution.phase();
    REQUIRE((run_is_live(started) || started == RunPhase::Finished));
    testing::run_script_patiently(session, json::parse(R"([{"wait_run": "finished"}])"));
    unsetenv("XDG_DATA_HOME");
    const auto fresh = studio.run.evolution.snapshot();
    REQUIRE(fresh);
    CHECK(fresh->loaded);
    CHECK(fresh->experiment.name == "damaged");
    CHECK(fresh->generation == 1);
    CHECK(fresh->run_dir != (dir / "run").string());
    CHECK(fs::exists(fs::path(fresh->run_dir) / evo::kCheckpointFile));
    CHECK(studio.document.experiment().name == "damaged");
}

TEST_CASE("studio run states: a second resume that fails within one frame says so, not 'resumed'") {
    // Issue 39, a low (a stale status line): the line told of a run's end only when the run's
    // phase differed from the last one it had heard of. A resume that failed as the one before
    // it had, before a frame saw it running (one slow frame: 5-20 fps while evolving), left
    // "resumed ..." on the line, in black, over a run panel saying it failed.
    const auto dir = fs::absolute(testing::fresh_dir("states-failed-twice"));
    auto e = testing::tiny_experiment();
    e.evolution.generations = 1;
    write_run(dir / "run", e);
    for (const char* name : {evo::kCheckpointFile, evo::kPreviousCheckpointFile})
        std::ofstream(dir / "run" / name) << "{ damaged";

    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1024, 700);
    for (int attempt = 1; attempt <= 2; ++attempt) {
        CAPTURE(attempt);
        REQUIRE(resume_run_directory(studio, (dir / "run").string()));
        // The run fails before the next frame begins.
        REQUIRE(bhm::test::wait_until(
            [&] {
                const auto run = studio.run.evolution.snapshot();
                return run && run->phase == RunPhase::Failed;
            },
            [] { std::this_thread::sleep_for(std::chrono::milliseconds(2)); }));
        session.frame();
        CHECK(studio.ui.status_is_error);
        CHECK_MESSAGE(studio.ui.status.find("no usable checkpoint") != std::string::npos,
                      studio.ui.status);
    }
}

namespace {

// As the Run panel reads it: the progress first, then the snapshot (studio.run.progress).
double live_elapsed(const Studio& s) {
    const LiveProgress progress = s.run.evolution.progress();
    const auto run = s.run.evolution.snapshot();
    return live_figures(*run, progress, s.run.evolution.phase()).elapsed_s;
}

}  // namespace

TEST_CASE("studio run states: rules sent on Resume end the edited-rules note, the clock never runs back") {
    const auto dir = testing::fresh_dir("states-rules");
    Studio studio;
    auto e = testing::tiny_experiment();
    // More than the test waits for: Stop must find the run live (8 generations ran out before
    // the Stop on a loaded machine, and "stopped" never came).
    e.evolution.generations = 500;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_generations": 1}])"));
    // Paused inside a generation with simulations done: its time so far is on the clock.
    REQUIRE(testing::frames_until(session, [&] {
        const auto p = studio.run.evolution.progress();
        return p.running && p.simulations_done >= 1;
    }));
    testing::run_script_patiently(session, json::parse(R"([{"click": "Pause"},
                                 {"wait_run": "paused"},
                                 {"set": "fitness.constraints.min_fill_fraction",
                                  "value": 0.05},
                                 {"frames": 2}])"));
    // Paused, with no replay playing and no body simulating: no redraw at full rate.
    studio.clock.playing = false;
    REQUIRE(testing::frames_until(session, [&] { return !studio.bodies.simulator.busy(); }));
    CHECK_FALSE(needs_animation(studio));
    // The note names what was edited (it named the measure, whatever the edit).
    CHECK(drawn_now(studio, "edited rules"));
    CHECK(describe_fitness_change(studio.run.evolution.snapshot()->experiment.fitness,
                                  studio.document.experiment().fitness) == "min fill 0.05");
    const double before = live_elapsed(studio);
    CHECK(before > 0.0);
    // Resume sends the rules: the note goes at once, not a generation later. The frozen
    // generation is abandoned and computed again under the new rules, and its time stays counted.
    run_script(session, json::parse(R"([{"click": "Resume"}])"));
    CHECK_FALSE(drawn_now(studio, "edited rules"));
    CHECK(needs_animation(studio));
    const int resumed_at = studio.run.evolution.snapshot()->generation;
    double last = live_elapsed(studio);
    CHECK(last >= before - 1e-9);
    double worst_step = 0.0;
    // The clock only moves forward: it went back by the abandoned attempt's time, and at the
    // end of a generation by the time its files took (its clock ran on while they were written).
    REQUIRE(testing::frames_until(session, [&] {
        const double now = live_elapsed(studio);
        worst_step = std::min(worst_step, now - last);
        last = now;
        CHECK_FALSE(drawn_now(studio, "edited rules"));
        return studio.run.evolution.snapshot()->generation > resumed_at + 1;
    }));
    CHECK_MESSAGE(worst_step >= -1e-9, "the elapsed time went back by " << -worst_step << " s");
    const auto run = studio.run.evolution.snapshot();
    CHECK(run->experiment.fitness.constraints.min_fill_fraction == 0.05);
    CHECK(run->elapsed_s >= before);
    testing::run_script_patiently(session,
                                  json::parse(R"([{"click": "Stop"}, {"wait_run": "stopped"}])"));
}

TEST_CASE("studio run states: after Stop and a resume of the folder the clock goes on, never back") {
    const auto dir = testing::fresh_dir("states-stop-clock");
    Studio studio;
    auto e = testing::tiny_experiment();
    e.evolution.generations = 6;
    e.evolution.population = 12;  // a generation long enough to stop inside it
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_generations": 1}])"));
    REQUIRE(testing::frames_until(session, [&] {
        const auto p = studio.run.evolution.progress();
        return p.running && p.simulations_done >= 2;
    }));
    double last = live_elapsed(studio);
    double worst_step = 0.0;
    auto watch = [&] {
        const double now = live_elapsed(studio);
        worst_step = std::min(worst_step, now - last);
        last = now;
    };
    run_script(session, json::parse(R"([{"click": "Stop"}])"));
    REQUIRE(testing::frames_until(session, [&] {
        watch();
        return studio.run.evolution.phase() == RunPhase::Stopped;
    }));
    for (int i = 0; i < 3; ++i) {
        session.frame();
        watch();
    }
    const double at_stop = last;
    // The checkpoint holds the stopped generation's time: what a resume goes on from.
    const auto state = evo::load_checkpoint((dir / "run").string());
    CHECK(state.state.elapsed_s == doctest::Approx(at_stop).epsilon(1e-9));
    REQUIRE(resume_run_directory(studio, (dir / "run").string()));
    REQUIRE(testing::frames_until(session, [&] {
        const auto run = studio.run.evolution.snapshot();
        if (run && run->loaded) watch();
        return run && run->loaded && studio.run.evolution.progress().simulations_done >= 1;
    }));
    CHECK(last >= at_stop);
    CHECK_MESSAGE(worst_step >= -1e-9, "the elapsed time went back by " << -worst_step << " s");
    testing::run_script_patiently(session,
                                  json::parse(R"([{"click": "Stop"}, {"wait_run": "stopped"}])"));
}

TEST_CASE("studio run states: a new run never plays the last run's champion under its name") {
    const auto dir = testing::fresh_dir("states-champion");
    Studio studio;
    auto e = testing::tiny_experiment();
    e.name = "first";
    e.evolution.generations = 1;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "first").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_run": "finished"},
                                                           {"wait_simulation": true}])"));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->experiment.name == "first");
    e.name = "second";
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "second").string();
    run_script(session, json::parse(R"([{"click": "Start"}])"));
    CHECK_FALSE(studio.bodies.shown);  // not the first run's body under the second run's panel
    testing::run_script_patiently(session, json::parse(R"([{"wait_run": "finished"},
                                                           {"wait_simulation": true}])"));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->experiment.name == "second");
}

TEST_CASE("studio run states: stopping or quitting in generation 0 leaves no empty run folder") {
    const auto dir = testing::fresh_dir("states-gen0");
    auto e = testing::tiny_experiment();
    e.evolution.population = 60;  // generation 0 lasts long enough to stop it
    {
        Studio studio;
        studio.document.reset(e, "");
        studio.run.dir_field = (dir / "stopped").string();
        HeadlessStudio session(studio, 1024, 700);
        run_script(session, json::parse(R"([{"click": "Start"}, {"frames": 2}])"));
        REQUIRE(fs::exists(dir / "stopped" / "run.json"));
        testing::run_script_patiently(session, json::parse(R"([{"click": "Stop"},
                                                               {"wait_run": "stopped"},
                                                               {"frames": 2}])"));
        CHECK_FALSE(fs::exists(dir / "stopped"));
        CHECK(studio.run.evolution.snapshot()->message.find("no checkpoint") != std::string::npos);
        // A run that had completed a generation keeps everything (tested in the session tests);
        // quitting mid-generation 0 is the same stop, at the studio's end.
        studio.run.dir_field = (dir / "quit").string();
        run_script(session, json::parse(R"([{"click": "Start"}, {"frames": 2}])"));
        REQUIRE(fs::exists(dir / "quit" / "run.json"));
    }
    CHECK_FALSE(fs::exists(dir / "quit"));
    // A folder that held something before the run is left as it was.
    fs::create_directories(dir / "kept");
    std::ofstream(dir / "kept" / "notes.txt") << "mine";
    {
        Studio studio;
        studio.document.reset(e, "");
        studio.run.dir_field = (dir / "kept").string();
        HeadlessStudio session(studio, 1024, 700);
        testing::run_script_patiently(
            session, json::parse(R"([{"click": "Start"}, {"frames": 2}, {"click": "Stop"},
                                     {"wait_run": "stopped"}])"));
    }
    CHECK(fs::exists(dir / "kept" / "notes.txt"));
}

TEST_CASE("studio run states: after Stop, Resume goes on from the run's folder, nothing typed") {
    // Issue 39, M1: after Stop, Resume was greyed and the run-directory field empty; resuming
    // needed the path typed into a collapsed section.
    const auto dir = fs::absolute(testing::fresh_dir("states-stop-resume"));
    Studio studio;
    auto e = testing::tiny_experiment();
    e.evolution.generations = 6;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_generations": 1},
                                                           {"click": "Stop"},
                                                           {"wait_run": "stopped"}])"));
    const int stopped_at = studio.run.evolution.snapshot()->generation;
    REQUIRE(stopped_at >= 1);
    REQUIRE(stopped_at < 6);  // the budget leaves something to resume
    // The Run directory section holds the folder, so Resume run works from there too.
    CHECK(studio.run.open_field == (dir / "run").lexically_normal().string());
    run_script(session, json::parse(R"([{"click": "Resume"}, {"frames": 2}])"));
    CHECK_MESSAGE(run_is_live(studio.run.evolution.phase()), studio.ui.status);
    testing::run_script_patiently(session, json::parse(R"([{"wait_run": "finished"}])"));
    const auto run = studio.run.evolution.snapshot();
    CHECK(run->generation == 6);
    CHECK(run->history.size() == 6);
    CHECK(run->run_dir == (dir / "run").lexically_normal().string());
}
