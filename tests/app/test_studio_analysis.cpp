// The researcher's analysis tools: time series and colour fields of a simulated body against
// hand-built replays (exact geometry), and scripted headless sessions of the champion history,
// side-by-side replay, the age-vs-fitness scatter, the replay-synchronised time plots and
// overlaid runs.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>

#include "../engine/muscle_test_support.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/session/body_analysis.hpp"
#include "app/gui/session/replay_player.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/view/viewport.hpp"
#include "render/colormap.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A rod of `n` voxels along x on a n x 1 x 1 lattice, at rest, with frames at 0, settle, ...
engine::Replay rod_replay(int n, double L, double settle_s) {
    engine::Replay r;
    r.nx = n, r.ny = 1, r.nz = 1;
    r.voxel_size_m = L;
    r.settle_s = settle_s;
    for (int v = 0; v < n; ++v) {
        r.voxel_cell.push_back(v);
        r.voxel_material.push_back(v % 2 ? 2 : 1);  // alternating passive / active
        r.voxel_fixed.push_back(v == 0);
    }
    return r;
}

engine::VoxelPoses rod_frame(int n, double L, double t, double angle_rad, float scale = 1.0f) {
    engine::VoxelPoses f;
    f.time_s = t;
    for (int v = 0; v < n; ++v) {
        // Rotated about the y axis through the first voxel's centre (a bent cantilever).
        const double r = v * L;
        f.position_m.insert(
            f.position_m.end(),
            {static_cast<float>(0.5 * L + r * std::cos(angle_rad)), static_cast<float>(0.5 * L),
             static_cast<float>(0.5 * L + r * std::sin(angle_rad))});
        f.orientation.insert(f.orientation.end(), {1.0f, 0.0f, 0.0f, 0.0f});
        const float s = static_cast<float>(L) * scale;
        f.size_m.insert(f.size_m.end(), {s, s, s});
    }
    return f;
}

}  // namespace

TEST_CASE("studio analysis: bend angle, tip and centre of mass of a rotated rod") {
    const int n = 5;
    const double L = 0.01, settle = 0.1;
    auto e = testing::tiny_experiment({n, 1, 1});
    auto r = rod_replay(n, L, settle);
    const double angle = 0.3;  // rad
    r.frames = {rod_frame(n, L, 0.0, 0.0), rod_frame(n, L, settle, 0.0),
                rod_frame(n, L, 0.2, angle, 1.1f)};
    std::vector<glm::vec3> com;
    for (const auto& f : r.frames) {
        glm::vec3 c(0.0f);
        for (int v = 0; v < n; ++v)
            c += glm::vec3(f.position_m[3 * v], f.position_m[3 * v + 1], f.position_m[3 * v + 2]);
        com.push_back(c / float(n));
    }
    const auto s = body_time_series(e, r, com);
    REQUIRE(s.t_s.size() == 3);
    CHECK(s.bend_deg[0] == 0.0);
    CHECK(s.bend_deg[1] == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(s.bend_deg[2] == doctest::Approx(angle * 180.0 / std::numbers::pi).epsilon(1e-4));
    // The tip (x = n-1 layer) moved along a circle of radius (n-1) L by `angle`: chord length.
    CHECK(s.tip_vox[2] == doctest::Approx(2.0 * (n - 1) * std::sin(angle / 2.0)).epsilon(1e-4));
    // The centre of mass (mean radius 2 L) moved by the same rotation.
    const double rx = 2.0 * (std::cos(angle) - 1.0), rz = 2.0 * std::sin(angle);
    CHECK(s.com_vox[0][2] == doctest::Approx(rx).epsilon(1e-4));
    CHECK(s.com_vox[2][2] == doctest::Approx(rz).epsilon(1e-4));
    CHECK(s.com_vox[1][2] == doctest::Approx(0.0).epsilon(1e-6));

    // Colour fields at the last frame.
    const auto d = voxel_scalars(ColorBy::Displacement, e, r, 2, s, {});
    CHECK(d.values[0] == doctest::Approx(0.0));
    CHECK(d.values[4] == doctest::Approx(2.0 * 4 * std::sin(angle / 2.0)).epsilon(1e-4));
    CHECK(d.range.max == doctest::Approx(d.values[4]).epsilon(1e-4));
    const auto strain = voxel_scalars(ColorBy::Strain, e, r, 2, s, {});
    CHECK(strain.values[3] == doctest::Approx(1.1 * 1.1 * 1.1 - 1.0).epsilon(1e-4));
    CHECK(strain.range.min == doctest::Approx(-strain.range.max));
    // Actuation: sin(2 pi f (t - settle)) on the active material (2), 0 on the passive one.
    const auto act = voxel_scalars(ColorBy::Actuation, e, r, 2, s, {});
    const double signal = std::sin(2.0 * std::numbers::pi * e.actuation.frequency_hz * 0.1);
    CHECK(act.values[1] == doctest::Approx(signal).epsilon(1e-5));
    CHECK(act.values[2] == 0.0f);
    const auto settling = voxel_scalars(ColorBy::Actuation, e, r, 0, s, {});
    CHECK(settling.values[1] == 0.0f);
    // Phase (issue 44): the controller's phase on active voxels, the same at every frame.
    std::vector<float> phases(r.voxel_cell.size());
    for (std::size_t v = 0; v < phases.size(); ++v)
        phases[v] = 0.5f * static_cast<float>(v) - 1.0f;
    for (int frame : {0, 2}) {
        const auto ph = voxel_scalars(ColorBy::Phase, e, r, frame, s, VoxelDrive{phases, {}});
        CHECK(ph.values[1] == -0.5f);
        CHECK(ph.values[2] == 0.0f);  // passive
        CHECK(ph.range.max == doctest::Approx(std::numbers::pi));
    }
}

TEST_CASE("studio analysis: the fibre axis colour mode shows each muscle voxel's own axis") {
    // Issue 43: fibres per voxel. A 4 x 1 x 1 rod: passive, muscle with its own axis z, muscle
    // with the material's (y), muscle with its own axis x.
    const int n = 4;
    auto e = testing::tiny_experiment({n, 1, 1});
    auto& muscle = e.materials[1].physics;
    muscle.cte_per_c = 0.0;
    muscle.actuation_model = engine::ActuationModel::Muscle;
    muscle.muscle.contraction_strain = 0.1;
    muscle.muscle.fibre_axis = 1;
    evo::Body body;
    body.size = {n, 1, 1};
    body.cells = {1, 2, 2, 2};
    body.fibre = {engine::kMaterialFibreAxis, 2, engine::kMaterialFibreAxis, 0};
    auto r = rod_replay(n, 0.01, 0.1);
    r.voxel_material = {1, 2, 2, 2};
    r.frames = {rod_frame(n, 0.01, 0.0, 0.0), rod_frame(n, 0.01, 0.1, 0.0)};
    const VoxelDrive drive = voxel_drive(e, body, r);
    CHECK(drive.fibre_axis == std::vector<std::int8_t>{-1, 2, 1, 0});
    const auto s = body_time_series(e, r, std::vector<glm::vec3>(r.frames.size()));
    const auto field = voxel_scalars(ColorBy::FibreAxis, e, r, 1, s, drive);
    CHECK(field.without == std::vector<std::uint8_t>{1, 0, 0, 0});
    CHECK(field.map == render::ColorMapName::Axes);
    // x, y, z are three different colours, each the axes map's at its place in the range.
    std::vector<glm::vec4> colours;
    for (int v = 1; v < n; ++v)
        colours.push_back(
            render::sample_color_map(field.map, field.range.normalize(field.values[v])));
    CHECK(colours[0] == render::sample_color_map(render::ColorMapName::Axes, 1.0f));  // z
    CHECK(colours[1] == render::sample_color_map(render::ColorMapName::Axes, 0.5f));  // y
    CHECK(colours[2] == render::sample_color_map(render::ColorMapName::Axes, 0.0f));  // x
    CHECK(colours[0] != colours[1]);
    CHECK(colours[1] != colours[2]);
    CHECK(colours[0] != colours[2]);
    // A body without its own fibres: every muscle voxel takes its material's axis.
    body.fibre.clear();
    CHECK(voxel_drive(e, body, r).fibre_axis == std::vector<std::int8_t>{-1, 1, 1, 1});
}

TEST_CASE("studio analysis: a muscle voxel's actuation colour is its delayed activation") {
    // Issue 44: a controller's phase delays a muscle voxel's stimulus; the actuation colour is
    // -a(tau - delay) (it contracts), the twitch's closed form. A 3 x 1 x 1 rod: passive, muscle
    // at phase 0, muscle at phase pi / 2 (a quarter of its 1 s period: 0.25 s later).
    auto e = testing::tiny_experiment({3, 1, 1});
    auto& muscle = e.materials[1].physics;
    muscle.cte_per_c = 0.0;
    muscle.actuation_model = engine::ActuationModel::Muscle;
    muscle.muscle = engine::test::skeletal();
    auto r = rod_replay(3, 0.01, 0.1);
    r.voxel_material = {1, 2, 2};
    r.frames = {rod_frame(3, 0.01, 0.0, 0.0), rod_frame(3, 0.01, 0.1 + 0.26, 0.0)};
    const auto s = body_time_series(e, r, std::vector<glm::vec3>(r.frames.size()));
    const VoxelDrive drive{{0.0f, 0.0f, static_cast<float>(std::numbers::pi / 2.0)}, {}};
    const auto act = voxel_scalars(ColorBy::Actuation, e, r, 1, s, drive);
    // One twitch: rises for the 10 ms pulse, then decays with 60 ms.
    auto twitch = [](double t) {
        if (t <= 0.0) return 0.0;
        if (t <= 0.01) return 1.0 - std::exp(-t / 0.02);
        return (1.0 - std::exp(-0.5)) * std::exp(-(t - 0.01) / 0.06);
    };
    CHECK(act.values[0] == 0.0f);
    CHECK(std::fabs(act.values[1] + twitch(0.26)) < 1e-6);
    CHECK(std::fabs(act.values[2] + twitch(0.01)) < 1e-6);
    CHECK(act.values[2] < -0.3f);  // 10 ms into its own twitch: near its peak
}

TEST_CASE("studio analysis: a replay holding a huge finite value gets a finite colour bar") {
    // Issue 41: 3.4e38 (a float's largest) in a voxel's position and size made the colour ranges
    // +inf and "-inf to inf": they were found in float.
    const int n = 5;
    const double L = 0.01, settle = 0.1;
    auto e = testing::tiny_experiment({n, 1, 1});
    auto r = rod_replay(n, L, settle);
    r.frames = {rod_frame(n, L, 0.0, 0.0), rod_frame(n, L, settle, 0.0),
                rod_frame(n, L, 0.2, 0.3, 1.1f)};
    r.frames[2].position_m[3] = std::numeric_limits<float>::max();
    r.frames[2].size_m[3] = std::numeric_limits<float>::max();
    const std::vector<glm::vec3> com(r.frames.size(), glm::vec3(0.0f));
    const auto s = body_time_series(e, r, com);
    CHECK(std::isfinite(s.max_displacement_vox));
    CHECK(std::isfinite(s.max_abs_strain));
    for (const ColorBy by : {ColorBy::Displacement, ColorBy::Strain}) {
        const auto field = voxel_scalars(by, e, r, 2, s, {});
        INFO(field.range.min << " to " << field.range.max);
        CHECK(std::isfinite(field.range.min));
        CHECK(std::isfinite(field.range.max));
        CHECK(std::isfinite(field.range.max - field.range.min));
        CHECK(field.range.max > 1.0f);
        for (const float v : field.values) {
            const float t = field.range.normalize(v);
            CHECK(t >= 0.0f);
            CHECK(t <= 1.0f);
        }
    }
}

TEST_CASE("studio analysis: champion history, side by side, scatter, time plots, overlaid runs") {
    const auto dir = testing::fresh_dir("analysis");
    auto e = testing::tiny_experiment();
    e.evolution.generations = 3;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "first").string();
    HeadlessStudio session(studio, 1280, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                 {"wait_run": "finished"},
                                 {"click": "tab Champions"}, {"frames": 40}])"));
    // Every champion file is listed; a click replays that champion with the fitness it had.
    std::size_t files = 0;
    for (const auto& f : fs::directory_iterator(dir / "first" / "champions"))
        files += f.path().extension() == ".json";
    const auto& entries = studio.run.champion_history.entries();
    REQUIRE(entries.size() == files);
    const auto first = entries.front();
    testing::run_script_patiently(
        session, json::array({{{"click", "champion gen " + std::to_string(first.generation)}},
                              {{"wait_simulation", true}}}));
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->id == first.id);
    CHECK(studio.bodies.shown->fitness == doctest::Approx(first.fitness).epsilon(1e-9));
    // Beside it: the newest champion, drawn next to the first one.
    const auto last = entries.back();
    run_script(session, json::array({{{"click", "beside gen " + std::to_string(last.generation)}},
                                     {{"frames", 2}}}));
    // Simulated on its own worker.
    REQUIRE(testing::frames_until(session, [&] { return studio.bodies.compared != nullptr; }));
    CHECK(studio.bodies.compared->id == last.id);
    session.frame();
    CHECK(studio.ui.status.find("beside it") == 0);  // no stale "simulating ..." line
    run_script(session, json::parse(R"([{"mode": "simulation"}, {"frames": 2}])"));
    // Split (the default): the compared body in a pane of its own, right of the first, as wide.
    REQUIRE(split_view_active(studio));
    const auto left_pane = build_view_draw_list(studio).voxel_instance_count();
    {
        const auto& left = studio.ui.widgets.at("3d view");
        const auto& right = studio.ui.widgets.at("3d view compared");
        CHECK(right.frame == studio.ui.frame);
        CHECK(right.min.x >= left.max.x);
        CHECK(std::abs((right.max.x - right.min.x) - (left.max.x - left.min.x)) < 2.0f);
        CHECK(compared_view_draw_list(studio).voxel_instance_count() > 0);
        // Linked cameras: a drag in the second pane turns both.
        const float yaw0 = studio.view.camera.yaw_rad;
        drag_widget(session, "3d view compared", {80.0f, 0.0f});
        session.frame();
        CHECK(studio.view.camera.yaw_rad != yaw0);
        CHECK(studio.view.second.camera.yaw_rad == studio.view.camera.yaw_rad);
        // Unlinked: the second pane's camera turns alone, the first stays.
        run_script(session, json::parse(R"([{"click": "link cameras"}, {"frames": 1}])"));
        REQUIRE_FALSE(studio.view.link_cameras);
        const float yaw1 = studio.view.camera.yaw_rad;
        drag_widget(session, "3d view compared", {-120.0f, 0.0f});
        session.frame();
        CHECK(studio.view.camera.yaw_rad == yaw1);
        CHECK(studio.view.second.camera.yaw_rad != yaw1);
        // The first pane's drag leaves the second alone.
        const float yaw2 = studio.view.second.camera.yaw_rad;
        drag_widget(session, "3d view", {60.0f, 0.0f});
        session.frame();
        CHECK(studio.view.camera.yaw_rad != yaw1);
        CHECK(studio.view.second.camera.yaw_rad == yaw2);
    }
    // Split off: beside it along +y in one view.
    run_script(session, json::parse(R"([{"click": "split"}, {"frames": 1}])"));
    REQUIRE_FALSE(studio.view.split);
    CHECK_FALSE(split_view_active(studio));
    const auto both = build_view_draw_list(studio);
    studio.bodies.compared.reset();
    const auto one = build_view_draw_list(studio);
    CHECK(both.voxel_instance_count() > one.voxel_instance_count());
    CHECK(both.bounds.max.y > one.bounds.max.y);  // beside it along +y
    CHECK(left_pane == one.voxel_instance_count());  // split: the first pane has one body

    // Colour by displacement: the drawn voxels take the sequential map's colours of their
    // displacement from t = 0 (the material colours at t = 0, where nothing has moved).
    run_script(session, json::parse(R"([{"replay": {"time_s": 0.35, "playing": false}}])"));
    const auto by_material = build_view_draw_list(studio);
    studio.view.color_by = ColorBy::Displacement;
    const auto by_displacement = build_view_draw_list(studio);
    REQUIRE(by_displacement.boxes.size() == by_material.boxes.size());
    const auto& shown = *studio.bodies.shown;
    const auto field = voxel_scalars(ColorBy::Displacement, shown.experiment, shown.replay,
                                     frame_index_at(shown.replay, 0.35), shown.series, {});
    int matched = 0, body_boxes = 0;
    for (const auto& box : by_displacement.boxes) {
        if (box.voxel < 0) continue;
        ++body_boxes;
        // The view draws the surface voxels only: box.voxel indexes that subset.
        const auto k = static_cast<std::size_t>(box.voxel);
        const auto v =
            shown.surface_voxels.empty() ? k : static_cast<std::size_t>(shown.surface_voxels.at(k));
        const glm::vec4 expected =
            render::sample_color_map(field.map, field.range.normalize(field.values.at(v)));
        matched += std::abs(box.color.r - expected.r) < 0.02f &&
                   std::abs(box.color.g - expected.g) < 0.02f &&
                   std::abs(box.color.b - expected.b) < 0.02f;
    }
    CHECK(body_boxes > 0);
    CHECK(matched == body_boxes);
    studio.view.color_by = ColorBy::Material;

    // Time plots: dragging in the centre-of-mass plot moves the replay clock.
    run_script(session, json::parse(R"([{"replay": {"time_s": 0.0, "playing": false}},
                                        {"click": "tab Time plots"}, {"frames": 2},
                                        {"click": "time plot com"}])"));
    CHECK(studio.clock.time_s > 0.05);
    CHECK_FALSE(studio.clock.playing);
    REQUIRE(studio.bodies.shown);
    CHECK(studio.bodies.shown->series.t_s.size() == studio.bodies.shown->replay.frames.size());

    // The AFPO scatter shows the population.
    run_script(session, json::parse(R"([{"click": "tab Age vs fitness"}, {"frames": 2}])"));
    const auto it = studio.ui.widgets.find("scatter plot");
    REQUIRE(it != studio.ui.widgets.end());
    CHECK(it->second.frame >= studio.ui.frame - 1);

    // Another run overlaid on the fitness plot of the same measure.
    auto e2 = e;
    e2.evolution.seed = 11;
    studio.document.reset(e2, "");
    studio.run.dir_field = (dir / "second").string();
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_run": "finished"}])"));
    REQUIRE(add_compared_run(studio, (dir / "first").string()));
    CHECK_FALSE(add_compared_run(studio, (dir / "nowhere").string()));
    REQUIRE(studio.run.compared.size() == 1);
    REQUIRE(studio.run.compared[0].snapshot);
    CHECK(studio.run.compared[0].snapshot->history.size() == 3);
    session.frame();
    CHECK(studio.run.fitness_plot_overlays == 1);
}

TEST_CASE("studio analysis: exploit flags on the champion and in the population table") {
    const auto dir = testing::fresh_dir("exploits");
    auto e = testing::tiny_experiment();
    e.evolution.generations = 1;
    Studio studio;
    studio.document.reset(e, "");
    studio.run.dir_field = (dir / "run").string();
    HeadlessStudio session(studio, 1280, 800);
    testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                                           {"wait_run": "finished"}])"));
    // The live run's members carry the flags evolution computed for them.
    const auto live = studio.run.evolution.snapshot();
    REQUIRE_FALSE(live->population.empty());
    for (const auto& m : live->population)
        CHECK(m.exploits.checked);

    // A champion file flagged "escaped" (written by hand): the run directory view shows it.
    const auto champion_path = dir / "run" / "champion.json";
    json champion = json::parse(std::ifstream(champion_path));
    evo::ExploitReport flagged;
    flagged.checked = true;
    flagged.escaped = true;
    flagged.unanchored_fraction = 0.25;
    champion["report"]["exploits"] = evo::exploits_to_json(flagged);
    std::ofstream(champion_path) << champion.dump(2);
    REQUIRE(open_run_directory(studio, (dir / "run").string()));
    run_script(session, json::parse(R"([{"frames": 3}])"));
    REQUIRE(studio.run.snapshot->has_champion);
    CHECK(studio.run.snapshot->champion.exploits == flagged);
    CHECK(exploit_summary(flagged) == "escaped (25 % of the voxels unanchored)");
    CHECK(exploit_letters(flagged) == "E");
    const std::string cell = "flags #" + std::to_string(studio.run.snapshot->champion.id);
    REQUIRE(studio.ui.widgets.count(cell));
    CHECK(studio.ui.widgets.at(cell).frame >= studio.ui.frame - 1);
    // Replayed, the champion's flags are the overlay's.
    testing::run_script_patiently(session, json::parse(R"([{"select": "champion"},
                                                           {"wait_simulation": true}])"));
    const auto* shown = shown_exploits(studio);
    REQUIRE(shown);
    CHECK(shown->escaped);
}
