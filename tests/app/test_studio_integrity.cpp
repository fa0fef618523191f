// Run integrity of the studio, each through a scripted headless session (docs/studio.md steps):
// unsaved edits are never discarded without asking, the live run owns its experiment, plots keep
// measures apart, stop and start report what is true, the layout survives a tiny window, paths
// are absolute and presets are not overwritten, fast clicks land, simulation mode draws no tint.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/view/viewport.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/run/evolution_run.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

bool on_screen(const Studio& s, const std::string& widget) {
    const auto it = s.ui.widgets.find(widget);
    return it != s.ui.widgets.end() && it->second.frame >= s.ui.frame - 1;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Restores an environment variable when the test ends.
struct ScopedEnv {
    std::string name, old;
    bool had = false;
    ScopedEnv(const char* n, const std::string& value) : name(n) {
        if (const char* v = std::getenv(n)) {
            had = true;
            old = v;
        }
        setenv(n, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (had)
            setenv(name.c_str(), old.c_str(), 1);
        else
            unsetenv(name.c_str());
    }
};

}  // namespace

TEST_CASE("studio integrity: New, Open, recent files and Ctrl+Q ask before unsaved edits go") {
    const auto dir = testing::fresh_dir("unsaved");
    auto other = testing::tiny_experiment({4, 2, 2});
    other.name = "other";
    const auto other_path = (dir / "other.json").string();
    evo::save_experiment(other_path, other);

    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"set": "simulation.evaluate_s", "value": 0.25}])"));
    REQUIRE(studio.document.dirty());
    const auto edited = studio.document.experiment();

    // New asks; Cancel keeps the document and its undo history.
    run_script(session, json::parse(R"([{"click": "New"}, {"frames": 2}])"));
    CHECK(asking_unsaved(studio));
    CHECK(on_screen(studio, "Discard changes"));
    CHECK(studio.document.experiment() == edited);
    run_script(session, json::parse(R"([{"click": "Cancel"}])"));
    CHECK_FALSE(asking_unsaved(studio));
    CHECK(studio.document.experiment() == edited);
    CHECK(studio.document.undo_label() == "set simulation.evaluate_s");

    // Open... with a typed path (the dialog takes it with Enter) asks; Discard opens the file.
    studio.path_field = other_path;
    run_script(session,
               json::parse(R"([{"click": "Open..."}, {"key": "enter"}, {"frames": 2}])"));
    CHECK(asking_unsaved(studio));
    CHECK(studio.document.experiment() == edited);
    run_script(session, json::parse(R"([{"click": "Discard changes"}])"));
    CHECK(studio.document.experiment().name == "other");
    CHECK(fs::path(studio.settings.recent_files.front()).is_absolute());

    // A recent file (the Files tab) asks too; Save changes saves, then opens.
    run_script(session, json::parse(R"([{"set": "simulation.evaluate_s", "value": 0.2},
                                        {"click": "tab Files"}, {"frames": 2},
                                        {"click": "recent other.json"}, {"frames": 2}])"));
    CHECK(asking_unsaved(studio));
    run_script(session, json::parse(R"([{"click": "Save changes"}])"));
    CHECK_FALSE(asking_unsaved(studio));
    CHECK(evo::load_experiment(other_path).simulation.evaluate_s == 0.2);
    CHECK_FALSE(studio.document.dirty());

    // Ctrl+Q asks; the window's close button goes the same way (request_quit).
    run_script(session, json::parse(R"([{"set": "simulation.evaluate_s", "value": 0.3},
                                        {"key": "ctrl+q"}, {"frames": 2}])"));
    CHECK_FALSE(studio.ui.quit_requested);
    CHECK(asking_unsaved(studio));
    run_script(session, json::parse(R"([{"click": "Cancel"}])"));
    // The window's close button (what the GLFW runner calls): the window stays open and asks.
    CHECK_FALSE(window_close_requested(studio));
    run_script(session, json::parse(R"([{"frames": 2}])"));
    CHECK(asking_unsaved(studio));
    run_script(session, json::parse(R"([{"click": "Discard changes"}])"));
    CHECK(studio.ui.quit_requested);
}

TEST_CASE("studio integrity: quitting mid-run asks, the live run owns its experiment") {
    const auto dir = testing::fresh_dir("owns");
    auto e = testing::tiny_experiment();
    e.evolution.generations = 40;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_generations": 1},
                                                           {"click": "Pause"},
                                                           {"wait_run": "paused"}])"));
    // Another experiment, with another measure, opened while the run is paused.
    auto other = testing::tiny_experiment();
    other.fitness.measure = evo::FitnessMeasure::ComFinal3d;
    const auto other_path = (dir / "other.json").string();
    evo::save_experiment(other_path, other);
    json load = json::array({{{"load", other_path}}, {{"frames", 2}}});
    run_script(session, load);
    CHECK_FALSE(editing_run_document(studio));
    CHECK_FALSE(rules_differ_from_run(studio));
    CHECK_FALSE(apply_rules_to_run(studio));
    const int paused_at = studio.run.evolution.snapshot()->generation;
    testing::run_script_patiently(
        session, json::array({{{"click", "Resume"}}, {{"wait_generations", paused_at + 1}}}));
    auto run = studio.run.evolution.snapshot();
    CHECK(run->experiment.fitness.measure == evo::FitnessMeasure::BendAngleDeg);
    CHECK(run->rule_changes.empty());
    CHECK(read_text(dir / "run" / "run.json").find("com_final_3d") == std::string::npos);

    // Ctrl+Q while it runs asks; Cancel goes on, "Finish generation, then quit" pauses after
    // the generation in progress is saved, then quits.
    run_script(session, json::parse(R"([{"key": "ctrl+q"}, {"frames": 2}])"));
    CHECK(asking_quit_run(studio));
    CHECK_FALSE(studio.ui.quit_requested);
    run_script(session, json::parse(R"([{"click": "Cancel"}])"));
    CHECK(run_is_live(studio.run.evolution.phase()));
    CHECK(studio.run.evolution.phase() != RunPhase::Paused);
    const int before_quit = studio.run.evolution.snapshot()->generation;
    testing::run_script_patiently(session, json::parse(R"([{"key": "ctrl+q"},
                                 {"click": "Finish generation, then quit"},
                                 {"wait_run": "paused"},
                                 {"frames": 2}])"));
    CHECK(studio.ui.quit_requested);
    CHECK(studio.run.evolution.snapshot()->generation >= before_quit + 1);
}

TEST_CASE(
    "studio integrity: Stop in generation 0 says there is no checkpoint; Start shows the "
    "run at once") {
    const auto dir = testing::fresh_dir("stop0");
    auto e = testing::tiny_experiment({5, 3, 3});
    e.simulation.evaluate_s = 30.0;  // a generation 0 long enough to stop inside it
    e.evolution.population = 6;
    e.evolution.generations = 7;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    run_script(session, json::parse(R"([{"click": "Start"}])"));
    // The frame after Start: the run's own rules, budget and folder, no stale warning.
    REQUIRE(studio.run.snapshot);
    CHECK(studio.run.snapshot->loaded);
    CHECK(studio.run.snapshot->experiment == e);
    CHECK(studio.run.snapshot->generation_budget == 7);
    CHECK(studio.run.snapshot->run_dir == fs::absolute(dir / "run").lexically_normal().string());
    CHECK(editing_run_document(studio));
    CHECK_FALSE(rules_differ_from_run(studio));
    // Ctrl+Q now: the question promises no checkpoint (none exists before generation 0 ends).
    run_script(session, json::parse(R"([{"key": "ctrl+q"}])"));
    REQUIRE(asking_quit_run(studio));
    CHECK_MESSAGE(quit_run_question(studio).find("no checkpoint") != std::string::npos,
                  quit_run_question(studio));
    CHECK(quit_run_question(studio).find("is kept") == std::string::npos);
    answer_quit_run(studio, QuitRunAnswer::Cancel);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Stop"},
                                                           {"wait_run": "stopped"}])"));
    const auto run = studio.run.evolution.snapshot();
    CHECK(run->generation == 0);
    CHECK(run->message.find("no checkpoint") != std::string::npos);
    CHECK(run->message.find("stopped at a checkpoint") == std::string::npos);
    CHECK_FALSE(fs::exists(dir / "run" / "checkpoint.json"));
}

TEST_CASE(
    "studio integrity: Pause freezes the simulations in flight at once, Resume goes on: the run "
    "equals an uninterrupted twin; a resumed folder shows its history at once") {
    const auto dir = testing::fresh_dir("pause-twin");
    auto e = testing::tiny_experiment();
    e.simulation.evaluate_s = 6.0;  // generations long enough to pause inside one
    e.evolution.generations = 3;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 700);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_generations": 1}])"));
    // Pause inside generation 1, once some of its simulations are done. Until then the Run
    // panel's figures move inside the generation: elapsed grows, the progress bar is shown.
    const auto first = live_figures(*studio.run.evolution.snapshot(),
                                    studio.run.evolution.progress(), studio.run.evolution.phase());
    // Until the count has moved on from `first`: by the time the wait for generation 1 ends,
    // some of its simulations may be done already (more of them the more loaded the machine).
    REQUIRE(testing::frames_until(session, [&] {
        return live_figures(*studio.run.evolution.snapshot(), studio.run.evolution.progress(),
                            studio.run.evolution.phase())
                   .simulations > first.simulations;
    }));
    session.frame();
    const auto later = live_figures(*studio.run.evolution.snapshot(),
                                    studio.run.evolution.progress(), studio.run.evolution.phase());
    CHECK(studio.run.evolution.snapshot()->generation == 1);
    CHECK(later.elapsed_s > first.elapsed_s);
    CHECK(later.simulations > first.simulations);
    CHECK(later.eta_s > 0.0);
    CHECK(on_screen(studio, "generation progress"));
    run_script(session, json::parse(R"([{"click": "Pause"}])"));
    CHECK(studio.run.evolution.phase() == RunPhase::Paused);  // the frame after the click
    const auto frozen = studio.run.evolution.progress();
    MESSAGE("paused in generation " << frozen.generation << " after " << frozen.simulations_done
                                    << " / " << frozen.simulations_total << " simulations");
    const auto paused_at = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - paused_at < std::chrono::milliseconds(1500))
        session.frame();
    const auto still = studio.run.evolution.progress();
    CHECK(still.simulations_done == frozen.simulations_done);  // nothing moved while paused
    CHECK(still.generation_s == doctest::Approx(frozen.generation_s).epsilon(0.05));
    CHECK(studio.run.evolution.snapshot()->generation == 1);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Resume"},
                                                           {"wait_run": "finished"}])"));
    const auto run = studio.run.evolution.snapshot();

    evo::RunOptions options;  // the twin: in memory, never paused
    evo::EvolutionRun twin(e, options);
    twin.run();
    const auto& history = twin.state().history;
    REQUIRE(run->history.size() == history.size());
    for (std::size_t g = 0; g < history.size(); ++g)
        CHECK(run->history[g].best_fitness == history[g].best_fitness);
    REQUIRE(twin.state().champion);
    CHECK(run->champion.id == twin.state().champion->individual.id);

    // The folder resumed: its history, rules and experiment are shown before anything runs.
    studio.document.reset(testing::tiny_experiment({4, 4, 2}), "");
    REQUIRE(resume_run_directory(studio, (dir / "run").string()));
    testing::run_script_patiently(session, json::parse(R"([{"wait_run": "finished"}])"));
    REQUIRE(studio.run.snapshot);
    CHECK(studio.run.snapshot->loaded);
    CHECK(studio.run.snapshot->history.size() == 3);
    CHECK(studio.document.experiment() == e);  // the editor took the run's own experiment
}

TEST_CASE("studio integrity: a tiny resize does not squeeze the layout for good, edges drag") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1280, 800);
    run_script(session, json::parse(R"([{"frames": 2}])"));
    const TileLayout before = studio.ui.tiles;
    const PanelLayout preferred = studio.settings.layout;
    run_script(session, json::parse(R"([{"resize": [300, 200]}, {"frames": 3}])"));
    CHECK(studio.ui.tiles.right < before.right);
    run_script(session, json::parse(R"([{"resize": [1280, 800]}, {"frames": 2}])"));
    CHECK(studio.ui.tiles == before);
    CHECK(studio.settings.layout == preferred);

    // The right column widens from its edge; the replay panel grows from its top edge, bounded.
    run_script(session, json::parse(R"([{"drag": "splitter right", "by": [-100, 0]}])"));
    CHECK(studio.ui.tiles.right == doctest::Approx(before.right + 100.0f).epsilon(0.01));
    run_script(session, json::parse(R"([{"drag": "splitter replay", "by": [0, -3000]},
                                        {"frames": 5}])"));
    const float area = studio.ui.tiles.view + studio.ui.tiles.bottom;
    CHECK(studio.ui.tiles.view >= kMinView - 0.5f);
    CHECK(studio.ui.tiles.bottom <= area - kMinView + 0.5f);
    const TileLayout settled = studio.ui.tiles;
    run_script(session, json::parse(R"([{"frames": 5}])"));
    CHECK(studio.ui.tiles == settled);  // it stays where it was released
}

TEST_CASE("studio integrity: runs go to the data folder, paths are absolute, presets are kept") {
    const auto dir = testing::fresh_dir("paths");
    ScopedEnv data("XDG_DATA_HOME", (dir / "data").string());
    const auto presets = dir / "presets";
    fs::create_directories(presets);
    fs::copy_file(fs::path(BHM_SOURCE_DIR) / "assets" / "experiments" / "quick-demo.json",
                  presets / "quick-demo.json");
    const std::string shipped = read_text(presets / "quick-demo.json");

    Studio studio;
    studio.library.presets_dir = presets.string();
    auto e = testing::tiny_experiment();
    e.evolution.generations = 1;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1280, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_run": "finished"}])"));
    const auto run_dir = studio.run.evolution.snapshot()->run_dir;
    CHECK(fs::path(run_dir).is_absolute());
    CHECK(run_dir.rfind((dir / "data" / "bhm-studio" / "runs").string(), 0) == 0);
    CHECK(fs::exists(fs::path(run_dir) / "fitness.csv"));

    // The presets gallery opens a preset; Ctrl+S over it asks for a new name instead.
    run_script(session, json::parse(R"([{"click": "tab Files"}, {"frames": 2},
                                        {"click": "preset quick-demo"}, {"frames": 2}])"));
    CHECK(studio.document.experiment().name ==
          evo::load_experiment((presets / "quick-demo.json").string()).name);
    run_script(session, json::parse(R"([{"set": "simulation.settle_s", "value": 0.3},
                                        {"key": "ctrl+s"}])"));
    CHECK(read_text(presets / "quick-demo.json") == shipped);
    CHECK(studio.ui.status_is_error);
    CHECK(studio.ui.status.find("shipped preset") != std::string::npos);
    CHECK(studio.path_field.find("quick-demo-edited.json") != std::string::npos);
    CHECK(studio.document.dirty());
    run_script(session, json::parse(R"([{"click": "tab Experiment"}, {"frames": 2},
                                        {"click": "Save As..."}, {"key": "enter"}])"));
    CHECK_FALSE(studio.document.dirty());
    CHECK(evo::load_experiment(studio.path_field).simulation.settle_s == 0.3);
    CHECK(read_text(presets / "quick-demo.json") == shipped);

    // The file browser walks folders and opens experiment files (asking first when modified).
    studio.library.browser_dir = dir.string();
    run_script(session, json::parse(R"([{"set": "simulation.settle_s", "value": 0.25},
                                        {"click": "tab Files"}, {"frames": 3},
                                        {"click": "folder presets"}, {"frames": 3}])"));
    CHECK(studio.library.browser_dir == presets.string());
    run_script(session, json::parse(R"([{"click": "file quick-demo.json"}, {"frames": 2}])"));
    INFO("status: " << studio.ui.status << ", dirty " << studio.document.dirty() << ", path "
                    << studio.document.path());
    CHECK(asking_unsaved(studio));
    run_script(session, json::parse(R"([{"click": "Discard changes"}])"));
    CHECK(studio.document.path() == (presets / "quick-demo.json").string());
    CHECK_FALSE(studio.document.dirty());
}

TEST_CASE("studio integrity: a fast click (press and release in one batch) paints a face") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment({5, 4, 3}), "");
    HeadlessStudio session(studio, 1280, 800);
    const auto x_max = static_cast<std::size_t>(evo::Face::XMax);
    run_script(session, json::parse(R"([{"click_face": "x+", "fast": true}])"));
    CHECK(studio.document.experiment().boundary.faces[x_max] == evo::BoundaryKind::Fixed);
    run_script(session, json::parse(R"([{"click": "tab Constraints"}, {"frames": 2},
                                        {"click": "Undo", "fast": true}])"));
    CHECK(studio.document.experiment().boundary.faces[x_max] == evo::BoundaryKind::Free);
}

TEST_CASE("studio integrity: simulation mode draws no tinted faces and hatches fixed ones") {
    auto e = testing::tiny_experiment({2, 2, 1});
    Studio studio;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1024, 700);
    testing::request_tiny_body(studio, e, 1, "body");
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                 {"mode": "simulation"}, {"frames": 2}])"));
    const auto list = build_view_draw_list(studio);
    CHECK(list.translucent_triangles.empty());  // nothing tints the body or z-fights with it
    // The fixed x- face: green lines a tenth of a voxel outside the workspace (x < 0).
    const float L = static_cast<float>(e.voxel_size_m);
    int hatch = 0;
    for (const auto& v : list.lines)
        if (std::abs(v.position.x + 0.1f * L) < 1e-6f && v.color.g > 0.5f && v.color.r < 0.2f)
            ++hatch;
    CHECK(hatch >= 8);  // the outline's four segments and at least one hatch line
}

TEST_CASE("studio integrity: viewing a run over a saved document never lets Save overwrite it") {
    // Issue 39, H1: Run > Run directory > View replaced a saved experiment with the run's while
    // the path field still named the saved file, so the next Save wrote the run's experiment over
    // it (a fixed face, a frame and its material were lost).
    const auto dir = fs::absolute(testing::fresh_dir("integrity-view-over-saved"));
    auto run_experiment = testing::tiny_experiment();
    run_experiment.name = "the run";
    run_experiment.evolution.generations = 1;
    {
        evo::RunOptions options;
        options.out_dir = (dir / "run").string();
        evo::EvolutionRun(run_experiment, options).run();
    }
    auto mine = testing::tiny_experiment();
    mine.name = "mine";
    mine.boundary.faces[static_cast<int>(evo::Face::ZMin)] = evo::BoundaryKind::Fixed;
    const std::string my_file = (dir / "mine.json").string();
    evo::save_experiment(my_file, mine);
    const std::string saved_text = read_text(my_file);

    Studio studio;
    REQUIRE(open_experiment(studio, my_file));  // File > Open: the path field names the file
    CHECK(studio.path_field == my_file);
    CHECK_FALSE(studio.document.dirty());
    REQUIRE(open_run_directory(studio, (dir / "run").string()));
    // The editor shows the run's experiment, untitled, and says the saved file is kept.
    CHECK(studio.document.experiment().name == "the run");
    CHECK(studio.document.path().empty());
    CHECK(studio.path_field.empty());
    CHECK_MESSAGE(studio.ui.status.find(my_file + " is unchanged") != std::string::npos,
                  studio.ui.status);
    // Save asks for a name rather than writing over the file the editor held before.
    CHECK_FALSE(save_experiment(studio));
    CHECK(read_text(my_file) == saved_text);
    CHECK(evo::load_experiment(my_file) == mine);
}
