// Scripted headless checks of the studio's smaller promises: the Front view faces the front, a
// quick Ctrl+Z is not lost, a Champions row replays wherever it is clicked, a dialog shows only
// its own error, the exploit rejections have controls, a novelty run shows each member's
// novelty, and an idle studio does not redraw without a change.
#include <doctest/doctest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <filesystem>
#include <utility>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/cli/render_video.hpp"
#include "app/gui/actions/export_actions.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/redraw_gate.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/view/viewport.hpp"
#include "engine/limits.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/experiment_fields.hpp"
#include "evo/experiment/field_rules.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

bool drawn_now(const Studio& s, const std::string& widget) {
    const auto it = s.ui.widgets.find(widget);
    return it != s.ui.widgets.end() && it->second.frame == s.ui.frame;
}

}  // namespace

TEST_CASE("studio details: Front looks at the side the iso view shows, x to the right") {
    Studio studio;
    for (auto view : {render::NamedView::Iso, render::NamedView::Front}) {
        set_named_view(studio, view);
        const auto& c = studio.view.camera;
        CHECK(c.eye_direction().y < -0.5f);  // the eye on the -y side
        CHECK(c.right().x > 0.8f);           // x grows to the right
    }
    CHECK(studio.view.camera.orthographic);
}

TEST_CASE("studio details: a Ctrl+Z pressed and released between two frames still undoes") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 800, 500);
    run_script(session, json::parse(R"([{"set": "simulation.settle_s", "value": 0.2}])"));
    REQUIRE(studio.document.can_undo());
    run_script(session, json::parse(R"([{"key": "ctrl+z", "fast": true}, {"frames": 1}])"));
    CHECK(studio.document.experiment().simulation.settle_s == 0.1);
    CHECK_FALSE(studio.document.can_undo());
    run_script(session, json::parse(R"([{"key": "ctrl+y"}])"));  // held a frame: still works
    CHECK(studio.document.experiment().simulation.settle_s == 0.2);
}

TEST_CASE("studio details: quick keys in a prefilled path field all act, in their order") {
    // Issue 39, M2: at 5-20 fps a key pressed and released between two frames never reached a
    // text field (Ctrl+A, End, Backspace did nothing) and a typed path was spliced into the
    // proposed one.
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    studio.run.dir_field = "/data/proposed/run-1";
    HeadlessStudio session(studio, 1024, 700);
    run_script(session, json::parse(R"([{"click": "run dir"},
        {"key": "end", "fast": true}, {"key": "backspace", "fast": true},
        {"key": "backspace", "fast": true}, {"frames": 1}])"));
    CHECK(studio.run.dir_field == "/data/proposed/run");
    run_script(session, json::parse(R"([{"key": "ctrl+a", "fast": true}, {"type": "/mine/run"},
                                        {"frames": 1}])"));
    CHECK(studio.run.dir_field == "/mine/run");
    // All in one event batch (one slow frame): End, two Backspaces, then "s"; each key is taken
    // by a frame of its own, the character after them.
    auto& keys = session.input().keys;
    for (int key : {GLFW_KEY_HOME, GLFW_KEY_DELETE, GLFW_KEY_END, GLFW_KEY_BACKSPACE}) {
        keys.key(key, GLFW_PRESS, 0);
        keys.key(key, GLFW_RELEASE, 0);
    }
    keys.character('s');
    for (int i = 0; i < 8 && keys.pending(); ++i) session.frame();
    session.frame();
    CHECK_FALSE(keys.pending());
    CHECK(studio.run.dir_field == "mine/rus");
}

TEST_CASE("studio details: Ctrl+A and a path typed in one slow frame replace a prefilled path") {
    // Issue 39, M2, as a window delivers it: Ctrl goes down as a key of its own, A comes with
    // the Ctrl bit, both are up again and the new path is typed, all before the next frame (5-20
    // fps while evolving). The path was spliced into the proposed one.
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    studio.run.dir_field = "/data/proposed/run-1";
    HeadlessStudio session(studio, 1024, 700);
    run_script(session, json::parse(R"([{"click": "run dir"}])"));
    auto& keys = session.input().keys;
    keys.key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS, 0);
    keys.key(GLFW_KEY_A, GLFW_PRESS, GLFW_MOD_CONTROL);
    keys.key(GLFW_KEY_A, GLFW_RELEASE, GLFW_MOD_CONTROL);
    keys.key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE, GLFW_MOD_CONTROL);
    for (const char c : std::string("/mine/run"))
        keys.character(static_cast<unsigned int>(c));
    for (int i = 0; i < 8 && keys.pending(); ++i)
        session.frame();
    session.frame();
    CHECK_FALSE(keys.pending());
    CHECK(studio.run.dir_field == "/mine/run");
}

TEST_CASE("studio details: a second dialog does not show an older error") {
    const auto dir = testing::fresh_dir("details-dialog");
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 800, 500);
    CHECK_FALSE(open_experiment(studio, (dir / "missing.json").string()));  // an error...
    REQUIRE(studio.ui.status_is_error);
    run_script(session, json::parse(R"([{"set": "simulation.settle_s", "value": 0.2}])"));
    set_status(studio, "an earlier failure", true);
    request_new_experiment(studio);  // ...then an unrelated question
    run_script(session, json::parse(R"([{"frames": 3}])"));
    REQUIRE(drawn_now(studio, "Save changes"));
    CHECK_FALSE(drawn_now(studio, "dialog error"));
    // Its own failure is shown: Save with no file name.
    studio.path_field.clear();
    run_script(session, json::parse(R"([{"click": "Save changes"}, {"frames": 2}])"));
    CHECK(drawn_now(studio, "dialog error"));
    CHECK(studio.ui.pending.error.find("file name") != std::string::npos);
    run_script(session, json::parse(R"([{"click": "Cancel"}, {"frames": 2}])"));
    request_new_experiment(studio);  // asked again: clean
    run_script(session, json::parse(R"([{"frames": 3}])"));
    CHECK(drawn_now(studio, "Save changes"));
    CHECK_FALSE(drawn_now(studio, "dialog error"));
}

TEST_CASE("studio details: the exploit flags can be rejected from the Experiment panel") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    // Tall enough that the Fitness section's last controls are inside the window.
    HeadlessStudio session(studio, 1024, 1100);
    run_script(session, json::parse(R"([{"click": "tab Experiment"}, {"frames": 2}])"));
    // An edit in the editor is labelled as the same edit by a script: "set <path>".
    const std::pair<const char*, const char*> controls[] = {
        {"reject escaped", "fitness.constraints.reject_escaped"},
        {"reject detached motion", "fitness.constraints.reject_detached_motion"},
        {"reject tentacle", "fitness.constraints.reject_tentacle"}};
    for (const auto& [name, path] : controls) {
        INFO(name);
        REQUIRE(studio.ui.widgets.count(name));
        run_script(session, json::array({{{"click", name}}, {{"frames", 1}}}));
        CHECK(studio.document.undo_label() == std::string("set ") + path);
    }
    const auto& c = studio.document.experiment().fitness.constraints;
    CHECK(c.reject_escaped);
    CHECK(c.reject_detached_motion);
    CHECK(c.reject_tentacle);
}

TEST_CASE("studio details: novelty column, Champions rows replay from any cell, mesh and VTK") {
    const auto dir = testing::fresh_dir("details-novelty");
    Studio studio;
    auto e = testing::tiny_experiment();
    e.evolution.algorithm = evo::Algorithm::Novelty;
    e.evolution.novelty.k = 3;
    e.evolution.novelty.archive_threshold = 0.01;
    e.evolution.novelty.archive_capacity = 12;
    e.evolution.generations = 2;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1024, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                 {"wait_run": "finished"},
                                 {"wait_simulation": true},
                                 {"click": "tab Population"}, {"frames": 2}])"));
    const auto run = studio.run.evolution.snapshot();
    REQUIRE(!run->population.empty());
    for (const auto& m : run->population) CHECK(m.novelty >= 0.0);
    const std::string first = "novelty #" + std::to_string(run->population.front().id);
    CHECK(drawn_now(studio, first));

    run_script(session, json::parse(R"([{"click": "tab Champions"}, {"frames": 2}])"));
    const auto& entries = studio.run.champion_history.entries();
    REQUIRE(!entries.empty());
    const auto& oldest = entries.front();
    const std::string cell = "champion fitness gen " + std::to_string(oldest.generation);
    REQUIRE(drawn_now(studio, cell));
    set_status(studio, "");
    run_script(session, json::array({{{"click", cell}}, {{"frames", 1}}}));
    // The click starts its simulation; a tiny body's can finish within the frame, so the status
    // says it is simulating that champion or already shows it.
    const std::string generation = "of generation " + std::to_string(oldest.generation);
    const bool simulating = studio.ui.status.find("simulating the champion " + generation) == 0;
    const bool showing = studio.ui.status.find("showing champion #") == 0 &&
                         studio.ui.status.find(generation) != std::string::npos;
    CHECK_MESSAGE((simulating || showing), studio.ui.status);

    // The CLI's geometry exports from the Export tab: a mesh at rest and deformed, a series.
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                 {"replay": {"time_s": 0.3, "playing": false}},
                                 {"click": "tab Export"}, {"frames": 2}])"));
    studio.exports.mesh_path = (dir / "rest.stl").string();
    studio.exports.vtk_folder = (dir / "paraview").string();
    run_script(session, json::parse(R"([{"click": "Save mesh"}, {"frames": 1}])"));
    REQUIRE_MESSAGE(fs::exists(dir / "rest.stl"), studio.ui.status);
    const auto stl_size = fs::file_size(dir / "rest.stl");
    CHECK(stl_size > 84);
    CHECK((stl_size - 84) % 50 == 0);  // binary STL: header, count, 50 bytes a triangle
    studio.exports.mesh_path = (dir / "deformed.obj").string();
    run_script(session, json::parse(R"([{"click": "mesh deformed"}, {"click": "Save mesh"},
                                        {"frames": 1}])"));
    CHECK(studio.exports.mesh_deformed);
    CHECK_MESSAGE(studio.ui.status.find("at t = 0.3 s") != std::string::npos, studio.ui.status);
    CHECK(fs::exists(dir / "deformed.obj"));
    CHECK(fs::exists(dir / "deformed.mtl"));
    run_script(session, json::parse(R"([{"click": "Write ParaView series"}, {"frames": 1}])"));
    CHECK_MESSAGE(fs::exists(dir / "paraview" / "series.pvd"), studio.ui.status);
    CHECK(fs::exists(dir / "paraview" / "com_path.vtp"));
    if (!app::find_on_path("ffmpeg")) {
        MESSAGE("no ffmpeg on PATH: the video export is not tried");
        return;
    }
    studio.exports.video_path = (dir / "replay.gif").string();
    studio.exports.frames_width = 160;
    studio.exports.frames_height = 100;
    studio.exports.frames_fps = 10.0;
    run_script(session, json::parse(R"([{"click": "Write video"}, {"frames": 8}])"));
    CHECK_FALSE(studio.exports.frame_job.active);
    CHECK_MESSAGE(fs::exists(dir / "replay.gif"), studio.ui.status);
    CHECK_MESSAGE(studio.ui.status.find("video written (5 frames)") == 0, studio.ui.status);
}

TEST_CASE("studio details: idle, the window draws only after a change or once a second") {
    Studio studio;
    RedrawGate gate;
    int drawn = 0;
    for (int i = 0; i < 10; ++i)
        drawn += gate.should_draw(studio, 0.01 * i);
    CHECK(drawn == RedrawGate::kSettleFrames);  // the first frames, then nothing
    CHECK(gate.should_draw(studio, 1.2));       // once a second
    CHECK_FALSE(gate.should_draw(studio, 1.3));
    gate.input();
    CHECK(gate.should_draw(studio, 1.31));  // input: a few frames to settle
    studio.clock.playing = true;            // a replay plays: every frame
    CHECK(needs_animation(studio));
    for (int i = 0; i < 5; ++i) CHECK(gate.should_draw(studio, 1.4 + 0.01 * i));
}

TEST_CASE("studio details: the splitters show a grip at rest") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1280, 800);  // wide: the left column is not folded
    run_script(session, json::parse(R"([{"frames": 2}])"));
    const render::Image image = session.capture();  // top row first
    for (const char* name : {"splitter left", "splitter right", "splitter replay", "splitter run",
                             "splitter plot"}) {
        INFO(name);
        const WidgetRect r = studio.ui.widgets.at(name);
        const int x = static_cast<int>(std::lround((r.min.x + r.max.x) * 0.5f));
        const int y = static_cast<int>(std::lround((r.min.y + r.max.y) * 0.5f));
        // The middle dot is darker than the window's background beside the strip.
        const auto* dot = image.pixel(x, y);
        const bool vertical = r.max.y - r.min.y > r.max.x - r.min.x;
        const auto* beside = vertical ? image.pixel(x, y + 8) : image.pixel(x + 8, y);
        CHECK(int(dot[0]) + 30 < int(beside[0]));
    }
}

TEST_CASE("studio details: an experiment field's tooltip is the field table's") {
    Studio studio;
    studio.document.reset(testing::tiny_experiment(), "");
    HeadlessStudio session(studio, 1024, 900);
    run_script(session, json::parse(R"([{"click": "tab Experiment"}, {"frames": 2}])"));
    auto hover = [&](const std::string& widget) {
        REQUIRE(drawn_now(studio, widget));
        const auto& r = studio.ui.widgets.at(widget);
        studio.ui.shown_tooltip.clear();
        session.input().mouse = {(r.min.x + r.max.x) / 2, (r.min.y + r.max.y) / 2};
        session.frame();
        session.frame();
        return studio.ui.shown_tooltip;
    };
    auto toggle = [&](const char* header) {
        run_script(session, json::array({{{"click", header}}, {{"frames", 2}}}));
    };
    for (const char* path : {"workspace.size", "simulation.settle_s", "fitness.measure",
                             "fitness.constraints.min_fill_fraction"}) {
        CAPTURE(path);
        const std::string shown = hover(path);
        CHECK(shown == evo::field_tooltip(*evo::find_experiment_field(path)));
        CHECK(shown.find(evo::find_experiment_field(path)->help) == 0);
    }
    // The two that had drifted (issue 22): Poisson's range and the amplitude's strain bound are
    // now the engine's constants (engine/limits.hpp), not copies.
    toggle("header Materials");
    const std::string poisson = hover("materials[0].poisson_ratio");
    CHECK(poisson == evo::field_tooltip(*evo::find_material_field("poisson_ratio")));
    CHECK(poisson.find("[" + evo::range_number(engine::limits::kMinPoissonRatio) + ", " +
                       evo::range_number(engine::limits::kMaxPoissonRatio) + "]") !=
          std::string::npos);
    toggle("header Materials");
    toggle("header Actuation");
    const std::string amplitude = hover("actuation.temperature_amplitude_c");
    CHECK(amplitude ==
          evo::field_tooltip(*evo::find_experiment_field("actuation.temperature_amplitude_c")));
    CHECK(amplitude.find("<= " + evo::range_number(engine::limits::kMaxActuationStrain)) !=
          std::string::npos);
    // The boundary's rows (issue 22), drawn by hand in the Constraints panel: their tooltips are
    // the table's too, rules between fields (field_rules.hpp) included.
    run_script(session, json::parse(R"([{"click": "tab Constraints"}, {"frames": 2}])"));
    for (const auto& [widget, path] :
         {std::pair{"face x-", "boundary.faces.x-"},
          std::pair{"frame z+", "boundary.enclosure.thickness_voxels.z+"},
          std::pair{"frame material", "boundary.enclosure.material"}}) {
        CAPTURE(widget);
        const std::string shown = hover(widget);
        CHECK(shown == evo::field_tooltip(*evo::find_experiment_field(path)));
        CHECK(shown.find(evo::rules_text(path)) != std::string::npos);
        CHECK_FALSE(evo::rules_text(path).empty());
    }
}

TEST_CASE("studio details: a click on the replayed body reads that voxel at the replay time") {
    Studio studio;
    auto e = testing::tiny_experiment();
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1024, 700);
    testing::request_tiny_body(studio, e, 3, "test body");
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                 {"replay": {"time_s": 0.35, "playing": false}},
                                 {"frames": 3}])"));
    REQUIRE(studio.bodies.shown);
    REQUIRE(studio.view.mode == ViewMode::Simulation);
    const auto& replay = studio.bodies.shown->replay;
    const auto poses = engine::pose_at(replay, studio.clock.time_s);
    // The voxel nearest the eye: nothing hides its centre.
    const glm::vec3 eye = studio.view.camera.eye_position();
    int nearest = -1;
    float best = 1e9f;
    for (int v = 0; v < poses.voxel_count(); ++v) {
        const auto i = static_cast<std::size_t>(v);
        const glm::vec3 p{poses.position_m[3 * i], poses.position_m[3 * i + 1],
                          poses.position_m[3 * i + 2]};
        if (glm::length(p - eye) < best) {
            best = glm::length(p - eye);
            nearest = v;
        }
    }
    const auto i = static_cast<std::size_t>(nearest);
    const glm::vec3 centre{poses.position_m[3 * i], poses.position_m[3 * i + 1],
                           poses.position_m[3 * i + 2]};
    const auto pixel = project_to_pixel(studio.view.camera, centre, studio.view.size_px);
    REQUIRE(pixel);
    // Through the mouse, as a person clicks: over the pixel, press, release.
    auto& input = session.input();
    input.mouse = studio.view.origin_px + *pixel;
    session.frame();
    input.buttons[0] = true;
    session.frame();
    input.buttons[0] = false;
    session.frame();
    session.frame();
    REQUIRE(studio.bodies.inspected_voxel == nearest);
    CHECK(drawn_now(studio, "voxel inspector"));
    const auto reading = inspected_voxel(studio);
    REQUIRE(reading);
    // The picked voxel is outlined in the 3D view as it is posed now: twelve edges of a box a
    // little larger than the voxel, centred on the replay's position of it.
    auto picked_box = [&]() {
        std::vector<glm::vec3> corners;
        for (const auto& v : build_view_draw_list(studio).lines_on_top)
            if (std::abs(v.color.r - 0.93f) < 1e-3f && std::abs(v.color.g - 0.49f) < 1e-3f)
                corners.push_back(v.position);
        return corners;
    };
    {
        const auto corners = picked_box();
        REQUIRE(corners.size() == 24);
        const glm::vec3 size{poses.size_m[3 * i], poses.size_m[3 * i + 1],
                             poses.size_m[3 * i + 2]};
        glm::vec3 mean{0.0f};
        for (const auto& p : corners) {
            mean += p / 24.0f;
            CHECK(glm::length(p - centre) ==
                  doctest::Approx(0.54f * glm::length(size)).epsilon(1e-3));
        }
        CHECK(glm::length(mean - centre) < 1e-3f * glm::length(size));
    }
    // Against the replay itself: the recorded frame at the clock, its first frame, the material.
    const auto& frame = replay.frames[static_cast<std::size_t>(
        frame_index_at(replay, studio.clock.time_s))];
    const auto& first = replay.frames.front();
    const float L = static_cast<float>(replay.voxel_size_m);
    glm::vec3 d{0.0f};
    for (int a = 0; a < 3; ++a) d[a] = frame.position_m[3 * i + a] - first.position_m[3 * i + a];
    CHECK(reading->displacement_vox == doctest::Approx(glm::length(d) / L).epsilon(1e-4));
    CHECK(reading->strain == doctest::Approx(frame.size_m[3 * i] * frame.size_m[3 * i + 1] *
                                                 frame.size_m[3 * i + 2] / (L * L * L) -
                                             1.0f)
                                 .epsilon(1e-4));
    CHECK(reading->material == replay.voxel_material[i]);
    CHECK(reading->material_name ==
          e.materials[static_cast<std::size_t>(reading->material - 1)].name);
    const int cell = replay.voxel_cell[i];
    CHECK(reading->cell == std::array<int, 3>{cell % replay.nx, (cell / replay.nx) % replay.ny,
                                              cell / (replay.nx * replay.ny)});
    // A click beside the body clears it.
    input.mouse = studio.view.origin_px + glm::vec2(3.0f, 3.0f);
    session.frame();
    input.buttons[0] = true;
    session.frame();
    input.buttons[0] = false;
    session.frame();
    CHECK(studio.bodies.inspected_voxel == -1);
    CHECK_FALSE(inspected_voxel(studio));
    CHECK(picked_box().empty());
}

TEST_CASE("studio details: exported frames carry a caption: experiment, body, fitness, time") {
    const auto dir = testing::fresh_dir("details-caption");
    Studio studio;
    auto e = testing::tiny_experiment();
    e.name = "caption test";
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1024, 700);
    testing::request_tiny_body(studio, e, 3, "champion #3, generation 2");
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                                           {"frames": 2}])"));
    REQUIRE(studio.bodies.shown);
    const auto lines = export_caption_lines(*studio.bodies.shown, 0.25);
    REQUIRE(lines.size() == 4);
    CHECK(lines[0] == "caption test");
    CHECK(lines[1] == "champion 3, generation 2");  // no '#': the dot font lacks it
    CHECK(lines[2].find("(bend_angle_deg)") != std::string::npos);
    CHECK(lines[3] == "t = 0.250 s");
    // With and without: the caption's box darkens the top-left corner of every frame.
    auto corner_mean = [](const render::Image& image) {
        double sum = 0.0;
        int n = 0;
        for (int y = 4; y < 24; ++y)
            for (int x = 4; x < 60; ++x, ++n) sum += image.pixel(x, y)[1];
        return sum / n;
    };
    double mean[2] = {0.0, 0.0};
    for (int with = 0; with < 2; ++with) {
        studio.exports.caption = with == 1;
        const auto folder = dir / (with ? "with" : "without");
        REQUIRE(start_frame_export(studio, folder.string(), 320, 200, 5.0));
        REQUIRE(testing::frames_until(session, [&] { return !studio.exports.frame_job.active; }));
        mean[with] = corner_mean(render::read_png((folder / "frame_00000.png").string()));
    }
    CHECK(mean[1] < 0.7 * mean[0]);
}
