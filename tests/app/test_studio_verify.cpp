// Verify in FEM in the studio (issue 27, docs/studio.md): the worker publishes its phases and
// lands the report in the run directory, Cancel kills the ccx child (or stops our engine's run)
// and leaves nothing behind, a missing ccx is said at once in the panel, a headless session
// verifies the champion or a Population row, draws the FEM's shape as a ghost and finds the
// report again when the run is reopened, and a crash's partial folders are cleared.
// The CalculiX cases skip (loudly) only where ccx is not installed.
#include <doctest/doctest.h>

#include "support/ccx_skip.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/session/fem_verifier.hpp"
#include "app/gui/shell/headless_studio.hpp"
#include "app/gui/shell/script.hpp"
#include "app/gui/view/scene.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/verify/ccx_run.hpp"
#include "test_studio_fixtures.hpp"

using namespace bhm;
using namespace bhm::app::gui;
using nlohmann::json;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

using bhm::test::skip_without_ccx;

// An nx x ny x nz bilayer held at x-: the bottom layer muscle (cte 0.01), the rest passive.
FemVerifyRequest bilayer_request(std::array<int, 3> size, const fs::path& run_dir) {
    auto e = testing::tiny_experiment(size);
    e.materials[0].physics.youngs_modulus_pa = 5e6;  // a stiff tissue: small strains, quick rest
    e.materials[1].physics.youngs_modulus_pa = 5e6;
    e.actuation.temperature_amplitude_c = 1.0;
    evo::Body body;
    body.size = size;
    body.cells.assign(static_cast<std::size_t>(body.cell_count()), 1);
    for (int y = 0; y < size[1]; ++y)
        for (int x = 0; x < size[0]; ++x)
            body.cells[static_cast<std::size_t>(body.index(x, y, 0))] = 2;
    FemVerifyRequest r;
    r.id = 7;
    r.label = "bilayer";
    r.experiment = e;
    r.framed_body = std::make_shared<const evo::Body>(evo::apply_frame_and_overrides(e, body));
    r.run_dir = run_dir.string();
    return r;
}

// Children of this process named ccx (from /proc), with their working folders.
std::vector<std::pair<int, std::string>> ccx_children() {
    std::vector<std::pair<int, std::string>> out;
    for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string name = entry.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream stat(entry.path() / "stat");
        std::string pid, comm, state;
        int ppid = 0;
        if (!(stat >> pid >> comm >> state >> ppid)) continue;
        if (ppid != static_cast<int>(::getpid()) || comm != "(ccx)") continue;
        std::error_code ec;
        out.push_back({std::stoi(pid), fs::read_symlink(entry.path() / "cwd", ec).string()});
    }
    return out;
}

bool partial_left(const fs::path& verify_dir) {
    std::error_code ec;
    if (!fs::exists(verify_dir, ec)) return false;
    for (const auto& entry : fs::directory_iterator(verify_dir))
        if (entry.path().filename().string().find(".partial") != std::string::npos) return true;
    return false;
}

// A pid that is surely gone: a child that has exited and been reaped.
long dead_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    REQUIRE(child > 0);
    ::waitpid(child, nullptr, 0);
    return static_cast<long>(child);
}

// A folder holding one file, as a half-written report is.
fs::path make_folder(const fs::path& path) {
    fs::create_directories(path);
    std::ofstream(path / "report.json") << "{}";
    return path;
}

// Sets PATH for the scope (the missing-ccx cases), then puts it back.
struct PathOverride {
    std::string saved;
    explicit PathOverride(const std::string& path)
        : saved(std::getenv("PATH") ? std::getenv("PATH") : "") {
        ::setenv("PATH", path.c_str(), 1);
    }
    ~PathOverride() { ::setenv("PATH", saved.c_str(), 1); }
};

// Polls the worker until its progress is in `phase` (true) or it has ended (false), for at most
// bhm::test::wait_limit_s().
bool seen_in_phase(const FemVerifier& verifier, evo::VerifyPhase phase) {
    bool seen = false;
    bhm::test::wait_until(
        [&] {
            if (!verifier.running()) return true;
            const auto st = verifier.state();
            seen = st && st->progress.phase == phase;
            return seen;
        },
        [] { std::this_thread::sleep_for(std::chrono::milliseconds(2)); });
    return seen;
}

}  // namespace

TEST_CASE("studio verify: the worker publishes its phases and lands the report in the run dir") {
    if (skip_without_ccx()) return;
    const auto dir = testing::fresh_dir("verify-phases");
    FemVerifier verifier;
    REQUIRE(verifier.start(bilayer_request({20, 2, 2}, dir)));
    std::vector<std::string> steps;  // each distinct step in the order it was seen
    bhm::test::wait_until(
        [&] {
            if (!verifier.running()) return true;
            const auto st = verifier.state();
            if (st && (steps.empty() || steps.back() != st->step)) steps.push_back(st->step);
            return false;
        },
        [] { std::this_thread::sleep_for(std::chrono::microseconds(500)); });
    REQUIRE_FALSE(verifier.running());
    const auto st = verifier.state();
    REQUIRE(st);
    INFO("error: " << st->error);
    REQUIRE(st->phase == FemVerifyPhase::Finished);
    std::string seen;
    for (const auto& s : steps)
        seen += s + " | ";
    INFO("steps seen: " << seen);
    auto position = [&](const std::string& step) {
        for (std::size_t k = 0; k < steps.size(); ++k)
            if (steps[k] == step) return static_cast<int>(k);
        return -1;
    };
    CHECK(position("CalculiX solving load 1 of 3") >= 0);
    CHECK(position("our engine at load 1 of 3") > position("CalculiX solving load 1 of 3"));
    CHECK(position("our engine at load 3 of 3") > position("our engine at load 1 of 3"));
    // Then the FEM's own mesh error, as bhm verify estimates it: a second mesh, FEM only.
    CHECK(position("mesh error: CalculiX solving the second mesh, load 1 of 3") >
          position("our engine at load 3 of 3"));
    CHECK(st->elapsed_s > 0.0);

    const fs::path kept = dir / "verify" / "individual-7";
    CHECK(verification_dir(dir.string(), 7) == kept.string());
    for (const char* file :
         {"report.json", "shapes.json", "fem-rest.vtk", "fem-plus-A.vtk", "fem-minus-A.vtk"})
        CHECK_MESSAGE(fs::exists(kept / file), file);
    CHECK_FALSE(partial_left(dir / "verify"));
    REQUIRE(st->result);
    const auto& v = *st->result;
    std::ifstream in(kept / "report.json");
    const json report = json::parse(in);
    CHECK(v.verdict == report.at("verdict").get<std::string>());
    // The 20x2x2 bilayer is 2 voxels across everywhere: the automatic mesh keeps C3D8I, 2 per
    // edge, and the mesh error compares it with 4.
    CHECK(v.mesh_reason == "C3D8I, 2 per voxel edge: every section at least 2 voxels across");
    REQUIRE(report.contains("fem_mesh_error"));
    CHECK(report["fem_mesh_error"]["elements_per_voxel_edge"] == 4);
    const double moved = report["fem_mesh_error"]["relative_difference"].get<double>();
    CHECK(moved > 0.0);
    CHECK(moved < 0.05);
    char expected[64];
    std::snprintf(expected, sizeof expected, "FEM mesh error ~%.1f %% (2 vs 4 per edge)",
                  100.0 * moved);
    CHECK(v.mesh_error == expected);
    REQUIRE(v.rows.size() == 3);
    CHECK(v.rows[1].load == "+A");
    CHECK(v.rows[1].fem_bend_deg ==
          doctest::Approx(report["loads"][1]["fem"]["bend_angle_deg"].get<double>()));
    // The ghost: 80 voxels per load, the FEM's tip voxel where the report's displacement puts it.
    REQUIRE(v.fem_shape.size() == 3);
    REQUIRE(v.voxel_cells.size() == 80);
    const int tip = report.at("tip_cell").get<int>();
    std::size_t k = 0;
    while (k < v.voxel_cells.size() && v.voxel_cells[k] != tip)
        ++k;
    REQUIRE(k < v.voxel_cells.size());
    const auto u = report["loads"][1]["fem"]["tip_displacement_m"].get<std::vector<double>>();
    const double l = 0.01;
    const double rest[3] = {(tip % 20 + 0.5) * l, (tip / 20 % 2 + 0.5) * l, (tip / 40 + 0.5) * l};
    for (int a = 0; a < 3; ++a)
        CHECK(v.fem_shape[1].position_m[3 * k + static_cast<std::size_t>(a)] ==
              doctest::Approx(rest[a] + u[static_cast<std::size_t>(a)]).epsilon(1e-4));
}

TEST_CASE("studio verify: Cancel kills ccx and leaves no report, no partial folder") {
    if (skip_without_ccx()) return;
    const auto dir = testing::fresh_dir("verify-cancel");
    FemVerifier verifier;
    // Large enough that CalculiX takes seconds: the cancel lands while it solves.
    REQUIRE(verifier.start(bilayer_request({20, 6, 6}, dir)));
    std::vector<std::pair<int, std::string>> solving;
    bhm::test::wait_until(
        [&] {
            if (!verifier.running()) return true;
            const auto st = verifier.state();
            if (st && st->step.rfind("CalculiX solving", 0) == 0) solving = ccx_children();
            return !solving.empty();
        },
        [] { std::this_thread::sleep_for(std::chrono::milliseconds(5)); });
    REQUIRE_MESSAGE(!solving.empty(), "ccx was never seen running");
    const auto cancelled_at = Clock::now();
    verifier.cancel();
    while (verifier.running() && Clock::now() - cancelled_at < std::chrono::seconds(30))
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const double took = std::chrono::duration<double>(Clock::now() - cancelled_at).count();
    MESSAGE("cancel took " << took << " s");
    CHECK(took < 2.0);
    const auto st = verifier.state();
    REQUIRE(st);
    CHECK(st->phase == FemVerifyPhase::Cancelled);
    CHECK(ccx_children().empty());
    for (const auto& [pid, cwd] : solving) {
        INFO("ccx pid " << pid << " worked in " << cwd);
        CHECK_FALSE(fs::exists(fs::path("/proc") / std::to_string(pid)));
        if (!cwd.empty()) CHECK_FALSE(fs::exists(cwd));  // its temporary folder went too
    }
    CHECK_FALSE(fs::exists(dir / "verify" / "individual-7"));
    CHECK_FALSE(partial_left(dir / "verify"));
}

TEST_CASE("studio verify: Cancel during the mesh error's second solve leaves no report") {
    if (skip_without_ccx()) return;
    const auto dir = testing::fresh_dir("verify-cancel-mesh-error");
    FemVerifier verifier;
    // The 20x2x2 bilayer: its second mesh (C3D8I, 4 per edge, 5120 elements) solves for seconds.
    REQUIRE(verifier.start(bilayer_request({20, 2, 2}, dir)));
    const bool second = seen_in_phase(verifier, evo::VerifyPhase::SecondMesh);
    REQUIRE_MESSAGE(second, "the mesh error's solve was never seen running");
    const auto cancelled_at = Clock::now();
    verifier.cancel();
    while (verifier.running() && Clock::now() - cancelled_at < std::chrono::seconds(30))
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const double took = std::chrono::duration<double>(Clock::now() - cancelled_at).count();
    MESSAGE("cancel during the second mesh took " << took << " s");
    CHECK(took < 2.0);
    const auto st = verifier.state();
    REQUIRE(st);
    CHECK(st->phase == FemVerifyPhase::Cancelled);
    CHECK(ccx_children().empty());
    CHECK_FALSE(fs::exists(dir / "verify" / "individual-7"));
    CHECK_FALSE(partial_left(dir / "verify"));
}

TEST_CASE("studio verify: a missing ccx is reported at once, nothing is started or written") {
    const auto dir = testing::fresh_dir("verify-no-ccx");
    const fs::path empty = dir / "empty-path";
    fs::create_directories(empty);
    PathOverride path(empty.string());
    FemVerifier verifier;
    CHECK(verifier.start(bilayer_request({4, 2, 2}, dir)));
    CHECK_FALSE(verifier.running());
    const auto st = verifier.state();
    REQUIRE(st);
    CHECK(st->phase == FemVerifyPhase::Failed);
    CHECK(st->error ==
          "ccx (CalculiX) is not on the PATH; install the Debian package calculix-ccx");
    CHECK_FALSE(fs::exists(dir / "verify"));
}

TEST_CASE("studio verify: Verify in FEM from the panel, the ghost in the view, kept on reopen") {
    if (skip_without_ccx()) return;
    const auto dir = testing::fresh_dir("verify-ui");
    const fs::path run_dir = dir / "run";
    std::string verdict;
    {
        Studio studio;
        studio.document.reset(testing::tiny_experiment({4, 2, 2}), "");
        studio.run.dir_field = run_dir.string();
        HeadlessStudio session(studio, 1024, 800);
        testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                     {"wait_run": "finished"},
                                     {"wait_simulation": true},
                                     {"click": "tab FEM"}, {"frames": 2}])"));
        REQUIRE(studio.bodies.shown);
        const auto id = studio.bodies.shown->id;
        CHECK_FALSE(studio.verify.result);  // nothing kept yet
        {
            // No ccx: the panel says so in red, the status line too; nothing hangs.
            const fs::path empty = dir / "empty-path";
            fs::create_directories(empty);
            PathOverride path(empty.string());
            run_script(session, json::parse(R"([{"click": "Verify in FEM"}, {"frames": 2}])"));
            CHECK(studio.ui.status_is_error);
            CHECK_MESSAGE(
                studio.ui.status.find("ccx (CalculiX) is not on the PATH") != std::string::npos,
                studio.ui.status);
            const auto it = studio.ui.widgets.find("fem error");
            CHECK((it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame));
        }
        testing::run_script_patiently(session, json::parse(R"([{"click": "Verify in FEM"},
                                                               {"wait_verify": true},
                                                               {"frames": 2}])"));
        REQUIRE_MESSAGE(studio.verify.result, studio.ui.status);
        CHECK(studio.verify.result->id == id);
        verdict = studio.verify.result->verdict;
        CHECK_MESSAGE(studio.ui.status.find(verdict) != std::string::npos, studio.ui.status);
        CHECK(fs::exists(fs::path(verification_dir(run_dir.string(), id)) / "report.json"));
        const auto it = studio.ui.widgets.find("fem verdict");
        CHECK((it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame));
        // Beside the verdict, the FEM's own mesh error; below it, the mesh and why.
        CHECK(studio.verify.result->mesh_error.rfind("FEM mesh error ~", 0) == 0);
        for (const char* widget : {"fem mesh error", "fem mesh"}) {
            const auto w = studio.ui.widgets.find(widget);
            CHECK_MESSAGE((w != studio.ui.widgets.end() && w->second.frame == studio.ui.frame),
                          widget);
        }

        // The 3D view: our static shape at +A with the FEM's as a ghost over it.
        set_view_mode(studio, ViewMode::Simulation);
        const FemVerification* overlay = fem_overlay(studio);
        REQUIRE(overlay);
        CHECK(studio.verify.result->rows[static_cast<std::size_t>(studio.verify.load)].load == "+A");
        render::Scene scene =
            simulation_scene(*studio.bodies.shown, studio.clock.time_s, studio.view);
        REQUIRE(apply_fem_overlay(scene, *overlay, studio.verify.load));
        REQUIRE(scene.ghost_poses);
        CHECK(scene.options.show_ghost);
        CHECK(scene.ghost_poses->voxel_count() == scene.body.voxel_count());
        CHECK(scene.options.com_trail_m.empty());
        const auto built = render::build_draw_list(scene);
        CHECK(built.translucent_boxes.size() >= static_cast<std::size_t>(scene.body.voxel_count()));
        run_script(session, json::parse(R"([{"click": "fem ghost"}, {"frames": 1}])"));
        CHECK_FALSE(studio.verify.ghost);
        CHECK_FALSE(fem_overlay(studio));
    }
    // Reopened: the champion shown again finds its report in the run directory.
    Studio again;
    HeadlessStudio session(again, 1024, 800);
    REQUIRE(open_run_directory(again, run_dir.string()));
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true},
                                                           {"click": "tab FEM"}, {"frames": 2}])"));
    REQUIRE(again.verify.result);
    CHECK(again.verify.result->verdict == verdict);
    CHECK_FALSE(again.verify.result->fem_shape.empty());
    const auto it = again.ui.widgets.find("fem verdict");
    CHECK((it != again.ui.widgets.end() && it->second.frame == again.ui.frame));
}

TEST_CASE("studio verify: Cancel during our engine's run stops within a slice, writes nothing") {
    if (skip_without_ccx()) return;
    const auto dir = testing::fresh_dir("verify-cancel-engine");
    auto request = bilayer_request({20, 4, 4}, dir);
    // One C3D8I per voxel: CalculiX is done in about a second. Our engine is asked for a rest
    // closer than it comes within a slice for seconds (no relative tolerance), so that its phase
    // lasts long enough for the cancel to land in it, not after it: uncancelled, its three loads
    // took 24 s on the shared 2-core build machine.
    request.options.mesh = evo::FemMeshOptions{evo::FemElement::C3D8I, 1};
    request.options.engine.tolerance = 0.0;
    request.options.engine.max_time_s = 30.0;
    FemVerifier verifier;
    REQUIRE(verifier.start(request));
    const bool in_engine = seen_in_phase(verifier, evo::VerifyPhase::Engine);
    REQUIRE_MESSAGE(in_engine, "our engine's phase was never seen");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // well inside its slices
    REQUIRE(verifier.running());
    const auto before = verifier.state();
    REQUIRE(before->progress.phase == evo::VerifyPhase::Engine);
    const auto cancelled_at = Clock::now();
    verifier.cancel();
    while (verifier.running() && Clock::now() - cancelled_at < std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const double took = std::chrono::duration<double>(Clock::now() - cancelled_at).count();
    MESSAGE("cancel during '" << before->step << "' took " << took << " s");
    const auto st = verifier.state();
    REQUIRE(st);
    CHECK(st->phase == FemVerifyPhase::Cancelled);  // not Finished: the run did not go on
    CHECK(took < 1.0);
    CHECK_FALSE(fs::exists(dir / "verify" / "individual-7"));
    CHECK_FALSE(partial_left(dir / "verify"));
}

TEST_CASE("studio verify: stale partial folders are removed, a live writer's and reports kept") {
    const auto dir = testing::fresh_dir("verify-stale");
    const fs::path v = dir / "verify";
    const auto aged = [](const fs::path& p) {
        fs::last_write_time(p, fs::file_time_type::clock::now() - std::chrono::hours(2));
        return p;
    };
    const std::string me = std::to_string(::getpid());
    const auto dead =
        make_folder(v / (".individual-3.partial-" + std::to_string(dead_pid()) + "-aB3dE9"));
    const auto mine = make_folder(v / (".individual-4.partial-" + me + "-aB3dE9"));
    const auto live = make_folder(v / ".individual-5.partial-1-aB3dE9");  // pid 1 lives
    const auto old_unnamed = aged(make_folder(v / ".individual-6.partial-Xy12Zw"));
    const auto young_unnamed = make_folder(v / ".individual-8.partial-Xy12Zw");
    const auto old_mine = aged(make_folder(v / (".individual-10.partial-" + me + "-Qq1Qq1")));
    const auto report = aged(make_folder(v / "individual-9"));
    const auto hidden = aged(make_folder(v / ".notes"));
    CHECK(remove_stale_partials(dir.string()) == 3);
    CHECK_FALSE(fs::exists(dead));         // its writer is gone
    CHECK_FALSE(fs::exists(old_unnamed));  // older than any write
    CHECK_FALSE(fs::exists(old_mine));
    CHECK(fs::exists(mine / "report.json"));  // this process may be writing it
    CHECK(fs::exists(live / "report.json"));
    CHECK(fs::exists(young_unnamed / "report.json"));
    CHECK(fs::exists(report / "report.json"));  // a finished report is never touched
    CHECK(fs::exists(hidden / "report.json"));
    CHECK(remove_stale_partials(dir.string()) == 0);
    CHECK(remove_stale_partials((dir / "nowhere").string()) == 0);
    CHECK(remove_stale_partials("") == 0);
}

TEST_CASE("studio verify: FEM on a Population row verifies that individual, kept on disk") {
    if (skip_without_ccx()) return;
    const auto dir = testing::fresh_dir("verify-population");
    const fs::path run_dir = dir / "run";
    std::int64_t id = -1;
    std::string verdict;
    {
        Studio studio;
        studio.document.reset(testing::tiny_experiment({4, 2, 2}), "");
        studio.run.dir_field = run_dir.string();
        HeadlessStudio session(studio, 1024, 800);
        testing::run_script_patiently(session, json::parse(R"([{"click": "Start"},
                                     {"wait_run": "finished"},
                                     {"click": "tab Population"}, {"frames": 2}])"));
        REQUIRE(studio.run.snapshot);
        // A member other than the champion (nor an earlier one): its row, not the champion's,
        // is what is verified, and a reopened run finds its body only in the checkpoint.
        const auto& history = studio.run.champion_history.entries();
        for (const auto& m : studio.run.snapshot->population)
            if (m.body &&
                !(studio.run.snapshot->has_champion && m.id == studio.run.snapshot->champion.id) &&
                std::none_of(history.begin(), history.end(),
                             [&](const ChampionEntry& e) { return e.id == m.id; })) {
                id = m.id;
                break;
            }
        REQUIRE(id >= 0);
        const std::string button = "verify #" + std::to_string(id);
        testing::run_script_patiently(session, json::array({{{"click", button}},
                                                            {{"wait_verify", true}},
                                                            {{"wait_simulation", true}},
                                                            {{"click", "tab FEM"}},
                                                            {{"frames", 2}}}));
        REQUIRE(studio.verify.state);
        INFO("error: " << studio.verify.state->error);
        CHECK(studio.verify.state->phase == FemVerifyPhase::Finished);
        CHECK(studio.verify.state->id == id);
        CHECK(studio.verify.state->label.rfind("individual #" + std::to_string(id), 0) == 0);
        REQUIRE(studio.bodies.shown);
        CHECK(studio.bodies.shown->id == id);  // the row's body is shown as well
        REQUIRE_MESSAGE(studio.verify.result, studio.ui.status);
        CHECK(studio.verify.result->id == id);
        verdict = studio.verify.result->verdict;
        CHECK(fs::exists(fs::path(verification_dir(run_dir.string(), id)) / "report.json"));
        const auto it = studio.ui.widgets.find("fem verdict");
        CHECK((it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame));
    }
    // A crash's leftover beside the report: opening the run clears it, the report stays.
    const auto crashed = make_folder(
        run_dir / "verify" / (".individual-99.partial-" + std::to_string(dead_pid()) + "-zZ9zZ9"));
    Studio again;
    HeadlessStudio session(again, 1024, 800);
    REQUIRE(open_run_directory(again, run_dir.string()));
    CHECK_FALSE(fs::exists(crashed));
    // A reopened run directory lists only its champions (the population is in the checkpoint):
    // Analysis > FEM lists the kept reports, and choosing the member's shows its body (from the
    // checkpoint) with its report and ghost, without solving.
    const std::string kept = "kept report #" + std::to_string(id);
    run_script(session, json::array({{{"click", "tab FEM"}}, {{"frames", 2}}}));
    CHECK(std::find(again.verify.kept_reports.begin(), again.verify.kept_reports.end(), id) !=
          again.verify.kept_reports.end());
    testing::run_script_patiently(
        session, json::array({{{"click", kept}}, {{"wait_simulation", true}}, {{"frames", 2}}}));
    CHECK_MESSAGE(again.ui.status.find("(checkpoint)") != std::string::npos, again.ui.status);
    REQUIRE(again.bodies.shown);
    CHECK(again.bodies.shown->id == id);
    REQUIRE_MESSAGE(again.verify.result, again.ui.status);
    CHECK(again.verify.result->id == id);
    CHECK(again.verify.result->verdict == verdict);
    CHECK_FALSE(again.verify.worker.running());  // shown, not solved again
    CHECK_FALSE(again.verify.state);
    const auto it = again.ui.widgets.find("fem verdict");
    CHECK((it != again.ui.widgets.end() && it->second.frame == again.ui.frame));
    set_view_mode(again, ViewMode::Simulation);
    const FemVerification* overlay = fem_overlay(again);
    REQUIRE(overlay);
    render::Scene scene = simulation_scene(*again.bodies.shown, again.clock.time_s, again.view);
    CHECK(apply_fem_overlay(scene, *overlay, again.verify.load));  // the ghost fits this body
}

TEST_CASE("studio verify: the kept reports of a run directory are listed by id") {
    const auto dir = testing::fresh_dir("verify-kept-list");
    const fs::path v = dir / "verify";
    make_folder(v / "individual-12");
    make_folder(v / "individual-3");
    make_folder(v / "individual-40");
    fs::remove(v / "individual-40" / "report.json");  // no report: not listed
    make_folder(v / ".individual-5.partial-1-aB3dE9");
    make_folder(v / "individual-x7");
    make_folder(v / "individual-");
    std::ofstream(v / "individual-8") << "a file, not a folder";
    CHECK(kept_verifications(dir.string()) == std::vector<std::int64_t>{3, 12});
    CHECK(kept_verifications((dir / "nowhere").string()).empty());
    CHECK(kept_verifications("").empty());
}

TEST_CASE("studio verify: the FEM tab with a finished result (golden)") {
    // A report as Verify in FEM writes it (the 20x2x2 bilayer of the phases case above, kept in
    // tests/data): the panel draws it without solving anything, so the picture is the same on
    // every machine. Only the Analysis tile is compared: the other tiles have their own goldens.
    auto kept = read_verification(
        (fs::path(BHM_SOURCE_DIR) / "tests" / "data" / "verify" / "individual-7").string(), 7);
    REQUIRE(kept);
    REQUIRE(kept->rows.size() == 3);
    kept->dir = "RUN_DIR/verify/individual-7";  // the checkout's path would differ per machine
    Studio studio;
    studio.verify.result = std::make_shared<const FemVerification>(std::move(*kept));
    studio.verify.load = 1;
    HeadlessStudio session(studio, 1280, 900);
    run_script(session, json::parse(R"([{"click": "tab FEM"}, {"frames": 3}])"));
    for (const char* widget :
         {"fem verdict", "fem ghost", "fem load rest", "fem load +A", "fem load -A"}) {
        const auto it = studio.ui.widgets.find(widget);
        CHECK_MESSAGE((it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame),
                      widget);
    }
    const auto tile = studio.ui.widgets.at("analysis panel");
    const render::Image screen = session.capture();
    const int x0 = static_cast<int>(tile.min.x), y0 = static_cast<int>(tile.min.y);
    const int x1 = std::min(screen.width, static_cast<int>(tile.max.x));
    const int y1 = std::min(screen.height, static_cast<int>(tile.max.y));
    REQUIRE(x1 - x0 > 100);
    REQUIRE(y1 - y0 > 100);
    render::Image panel(x1 - x0, y1 - y0);
    for (int y = y0; y < y1; ++y)
        std::copy_n(screen.pixel(x0, y), 4 * panel.width, panel.pixel(0, y - y0));
    testing::check_studio_golden("fem", panel, session.font());
}

TEST_CASE("studio verify: the verdict states its tolerance; the split view's lines stay in their pane") {
    // Issue 39, M6: the FEM verdict said "agrees within X %" without the tolerance it was judged
    // by (only a tooltip had it), and in the split view the overlay's lines ran under the right
    // pane.
    auto kept = read_verification(
        (fs::path(BHM_SOURCE_DIR) / "tests" / "data" / "verify" / "individual-7").string(), 7);
    REQUIRE(kept);
    REQUIRE(kept->compared);
    CHECK(fem_verdict_line(*kept) == kept->verdict + " (tolerance 10 %)");
    // A verdict that states its tolerance itself (every one written since issue 40) gets it once.
    FemVerification current = *kept;
    current.verdict = "differs by 27.7 % (tolerance 10 %) on the centre of mass";
    CHECK(fem_verdict_line(current) == current.verdict);

    auto e = testing::tiny_experiment({2, 2, 1});
    Studio studio;
    studio.document.reset(e, "");
    HeadlessStudio session(studio, 1024, 700);
    testing::request_tiny_body(studio, e, 1,
                               "champion #1 of generation 12 of a run whose name is long enough "
                               "to run past the left pane of the split view");
    testing::run_script_patiently(session, json::parse(R"([{"wait_simulation": true}])"));
    SimulationRequest other;
    other.id = 2;
    other.label = "champion #2 of generation 3, compared with the body on the left";
    other.experiment = e;
    other.framed_body = studio.bodies.shown->framed_body;
    studio.bodies.compare_simulator.request(other);
    REQUIRE(testing::frames_until(session, [&] { return studio.bodies.compared != nullptr; }));
    run_script(session, json::parse(R"([{"mode": "simulation"}, {"frames": 2}])"));
    REQUIRE(studio.view.split);
    for (const char* name : {"view overlay", "compared overlay"}) {
        const WidgetRect text = studio.ui.widgets.at(name);
        CHECK(text.frame == studio.ui.frame);
        const bool left = std::string(name) == "view overlay";
        const float pane_right = left ? studio.view.origin_px.x + studio.view.size_px.x
                                      : studio.view.second.origin_px.x + studio.view.second.size_px.x;
        CHECK_MESSAGE(text.max.x <= pane_right, name << " reaches " << text.max.x
                                                     << ", its pane ends at " << pane_right);
    }
}

TEST_CASE("studio verify: a damaged kept report is one readable line, not the JSON library's codes") {
    // Issue 39, a low: the FEM tab showed "[json.exception.parse_error.101] ..." for a kept
    // report.json cut short or of the wrong shape.
    const auto dir = testing::fresh_dir("verify-damaged-report");
    const std::vector<std::pair<std::string, std::string>> damaged = {
        {"cut short", R"({"verdict": "agrees", "status": )"},
        {"wrong type", R"({"verdict": 3, "status": "compared"})"},
    };
    for (const auto& [what, text] : damaged) {
        const fs::path report_dir = dir / ("individual-" + std::to_string(what.size()));
        fs::create_directories(report_dir);
        std::ofstream(report_dir / "report.json") << text;
        std::string message;
        try {
            read_verification(report_dir.string(), 1);
        } catch (const std::runtime_error& e) {
            message = e.what();
        }
        INFO(what << ": " << message);
        CHECK(message.find("report.json") != std::string::npos);
        CHECK(message.find("[json.exception") == std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE(
    "studio verify: a kept report or shapes file of the wrong shape names the file and the field") {
    // Issue 41 R9: a mistyped field of shapes.json reached the FEM tab as nlohmann's own text
    // ("[json.exception.type_error.302] type must be array, but is string"), and one of
    // report.json as "type must be number, but is string" without saying which field.
    const auto dir = testing::fresh_dir("verify-wrong-shape");
    const fs::path kept = fs::path(BHM_SOURCE_DIR) / "tests" / "data" / "verify" / "individual-7";
    const json report = json::parse(std::ifstream(kept / "report.json"));
    const json shapes = json::parse(std::ifstream(kept / "shapes.json"));
    struct Damage {
        const char* file;
        const char* pointer;  // the field damaged (RFC 6901)
        json value;           // its new value; null: the field removed
        const char* field;    // how the message names it
    };
    const std::vector<Damage> damages = {
        {"shapes.json", "/voxel_cells", "many", "voxel_cells"},
        {"shapes.json", "/loads/0/load", 5, "loads[0].load"},
        {"shapes.json", "/loads", json::object(), "loads"},
        {"report.json", "/fem/cpu_s", "fast", "fem.cpu_s"},
        {"report.json", "/loads/1/temperature_c", nullptr, "loads[1].temperature_c"},
        {"report.json", "/loads/2/fem/tip_displacement_m/1", "up",
         "loads[2].fem.tip_displacement_m"},
    };
    int id = 0;
    for (const auto& d : damages) {
        const fs::path folder = dir / ("individual-" + std::to_string(++id));
        fs::create_directories(folder);
        json damaged_report = report, damaged_shapes = shapes;
        json& target = std::string(d.file) == "report.json" ? damaged_report : damaged_shapes;
        const json::json_pointer at(d.pointer);
        if (d.value.is_null())
            target[at.parent_pointer()].erase(at.back());
        else
            target[at] = d.value;
        std::ofstream(folder / "report.json") << damaged_report.dump();
        std::ofstream(folder / "shapes.json") << damaged_shapes.dump();
        std::string message;
        try {
            read_verification(folder.string(), id);
        } catch (const std::runtime_error& e) {
            message = e.what();
        }
        INFO(d.file << " " << d.pointer << ": " << message);
        CHECK(message.rfind((folder / d.file).string() + ": " + d.field + ": ", 0) == 0);
        CHECK(message.find("[json.exception") == std::string::npos);
        CHECK(message.find("type must be") == std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

namespace {

// The message read_verification gives for a folder whose `fifo` is a named pipe, read on a thread:
// a reader that opens the pipe as a file blocks until a writer comes (the studio froze, issue 41
// R3), so after a generous wait (a loaded machine) the test plays the writer itself and fails
// instead of hanging.
std::string refusal_of_fifo(const fs::path& folder, const fs::path& fifo) {
    std::promise<std::string> answer;
    auto message = answer.get_future();
    std::thread reader([&] {
        try {
            read_verification(folder.string(), 7);
            answer.set_value("(read without an error)");
        } catch (const std::exception& e) {
            answer.set_value(e.what());
        }
    });
    const bool prompt = message.wait_for(std::chrono::seconds(30)) == std::future_status::ready;
    while (message.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
        const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // wakes a blocked open
        if (fd >= 0) ::close(fd);
    }
    reader.join();
    CHECK_MESSAGE(prompt, fifo.string() << " was waited on, not refused");
    return message.get();
}

}  // namespace

TEST_CASE(
    "studio verify: a FIFO named report.json or shapes.json is refused at once, not waited on") {
    const auto dir = testing::fresh_dir("verify-fifo");
    const fs::path kept = fs::path(BHM_SOURCE_DIR) / "tests" / "data" / "verify" / "individual-7";
    int id = 0;
    for (const char* name : {"report.json", "shapes.json"}) {
        const fs::path folder = dir / "verify" / ("individual-" + std::to_string(++id));
        fs::create_directories(folder);
        for (const char* file : {"report.json", "shapes.json"})
            if (std::string(file) != name) fs::copy_file(kept / file, folder / file);
        REQUIRE(::mkfifo((folder / name).c_str(), 0644) == 0);
        const std::string message = refusal_of_fifo(folder, folder / name);
        INFO(std::string(name) << ": " << message);
        CHECK(message.rfind((folder / name).string() + ": ", 0) == 0);  // names the file
        CHECK(message.find("not a regular file") != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
    // A FIFO report is not listed as a kept one (a FIFO shapes.json is, and refused when read).
    CHECK(kept_verifications(dir.string()) == std::vector<std::int64_t>{2});
}

TEST_CASE("studio verify: the FEM tab names the continuum law a nonlinear verdict was judged on") {
    // Issue 40: at large strain the verdict is judged on the nearer of two continuum laws
    // (evo/verify/verify_body, BodyVerification::laws); report.json's "law" is that line, shown
    // under the verdict. Older reports and linear steps have none, and show none.
    const fs::path kept = fs::path(BHM_SOURCE_DIR) / "tests" / "data" / "verify" / "individual-7";
    auto plain = read_verification(kept.string(), 7);
    REQUIRE(plain);
    CHECK(plain->law.empty());
    const auto dir = testing::fresh_dir("verify-law") / "individual-7";
    fs::create_directories(dir);
    json report = json::parse(std::ifstream(kept / "report.json"));
    const std::string line =
        "judged against the Neo-Hookean continuum, the nearer of two laws (Saint Venant-Kirchhoff: "
        "22.7 %); the two laws' answers differ by 44.9 % on the centre of mass's YZ displacement";
    report["law"] = line;
    std::ofstream(dir / "report.json") << report.dump(1);
    fs::copy_file(kept / "shapes.json", dir / "shapes.json");
    auto with_law = read_verification(dir.string(), 7);
    REQUIRE(with_law);
    CHECK(with_law->law == line);

    Studio studio;
    studio.verify.result = std::make_shared<const FemVerification>(std::move(*with_law));
    HeadlessStudio session(studio, 1280, 900);
    run_script(session, json::parse(R"([{"click": "tab FEM"}, {"frames": 3}])"));
    const auto it = studio.ui.widgets.find("fem law");
    CHECK((it != studio.ui.widgets.end() && it->second.frame == studio.ui.frame));
}
