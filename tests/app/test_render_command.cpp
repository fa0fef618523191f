// bhm render, run as a user runs it, and the experiment-to-scene mapping behind it.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "app/cli/render_scene.hpp"
#include "app/shell_run.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "render/image.hpp"
#include "render/replay_view.hpp"
#include "support/scratch.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bhm;

const std::string kSource = BHM_SOURCE_DIR;
const std::string kBhm = std::string(BHM_BINARY_DIR) + "/bin/bhm";
const std::string kExperiment =
    kSource + "/assets/experiments/quick-demo.json";  // 8 x 6 x 5, x- fixed

using Result = test::ShellResult;

Result run(const std::string& args, const std::string& env = "") {
    return test::run_shell(env + " " + kBhm + " render " + args);
}

// A workspace-sized temp folder with a 4 x 3 x 2 body (muscle on top) and a replay of it that
// sags over 1 s: every voxel moves down by 2 mm x t, the free end (x = 3) also along +x.
struct Fixture {
    // One folder per process: ctest runs test cases in parallel processes.
    fs::path dir = bhm::test::scratch_dir("render-cli");
    std::string body_path, replay_path;
    evo::Experiment experiment = evo::load_experiment(kExperiment);
    evo::Body body;

    Fixture() {
        body.size = {4, 3, 2};
        body.cells.assign(24, 1);
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x)
                body.cells[static_cast<std::size_t>(body.index(x, y, 1))] = 2;
        body_path = (dir / "body.json").string();
        evo::save_body(body_path, body);

        const auto spec =
            evo::make_body_spec(experiment, evo::apply_frame_and_overrides(experiment, body));
        const render::BodyView view = render::body_view_from_spec(spec);
        engine::Replay replay;
        replay.nx = spec.nx, replay.ny = spec.ny, replay.nz = spec.nz;
        replay.voxel_size_m = spec.voxel_size_m;
        replay.voxel_cell = view.voxel_cell;
        replay.voxel_material = view.voxel_material;
        replay.voxel_fixed = view.voxel_fixed;
        for (int f = 0; f <= 10; ++f) {
            engine::VoxelPoses poses = render::rest_poses(view);
            poses.time_s = 0.1 * f;
            for (int v = 0; v < view.voxel_count(); ++v) {
                const auto i = static_cast<std::size_t>(v);
                poses.position_m[3 * i + 2] -= static_cast<float>(0.002 * poses.time_s);
                if (view.voxel_coords(v)[0] == 3)
                    poses.position_m[3 * i] += static_cast<float>(0.004 * poses.time_s);
            }
            replay.frames.push_back(poses);
        }
        replay_path = (dir / "replay.bin").string();
        engine::write_replay(replay_path, replay);
    }
    ~Fixture() { fs::remove_all(dir); }
    std::string out(const std::string& name) const { return (dir / name).string(); }
};

// Share of pixels that differ by more than 16 in some channel.
double changed_fraction(const std::string& a, const std::string& b) {
    return render::compare_images(render::read_png(a), render::read_png(b), 16).fraction_over;
}

}  // namespace

TEST_CASE("bhm render draws a body at rest to a PNG of the asked size") {
    Fixture f;
    const auto r = run(kExperiment + " --body " + f.body_path + " --out " + f.out("rest.png") +
                       " --size 320x200");
    CHECK(r.status == 0);
    CHECK(r.output.find("wrote " + f.out("rest.png") + " (320x200, iso, at rest)") !=
          std::string::npos);
    const render::Image image = render::read_png(f.out("rest.png"));
    CHECK(image.width == 320);
    CHECK(image.height == 200);
    // Muscle (the experiment's red, 0.86 0.22 0.20) covers part of the picture.
    int red = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto* p = image.pixel(x, y);
            red += p[0] > 120 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
        }
    CHECK(red > 1000);
    // Other views render too, and differ from iso.
    for (const char* view : {"front", "top", "side"}) {
        const std::string path = f.out(std::string(view) + ".png");
        CHECK(run(kExperiment + " --body " + f.body_path + " --out " + path +
                  " --size 320x200 --view " + view)
                  .status == 0);
        CHECK(changed_fraction(path, f.out("rest.png")) > 0.05);
    }
}

TEST_CASE("bhm render shows a replay at a time, and a sequence of frames") {
    Fixture f;
    CHECK(run(kExperiment + " --replay " + f.replay_path + " --out " + f.out("t0.png") +
              " --time 0 --size 320x200")
              .status == 0);
    const auto r = run(kExperiment + " --replay " + f.replay_path + " --out " + f.out("t1.png") +
                       " --size 320x200");
    CHECK(r.status == 0);
    CHECK(r.output.find("t = 1.000 s") != std::string::npos);  // default: the last frame
    CHECK(changed_fraction(f.out("t0.png"), f.out("t1.png")) > 0.002);

    const auto seq = run(kExperiment + " --replay " + f.replay_path + " --frames 3 --out-dir " +
                         f.out("seq") + " --size 160x120 --color displacement");
    CHECK(seq.status == 0);
    CHECK(seq.output.find("colour scale: displacement 0 to") != std::string::npos);
    CHECK(seq.output.find("voxel lengths") != std::string::npos);
    for (const char* name : {"frame-00000.png", "frame-00001.png", "frame-00002.png"})
        CHECK(fs::exists(fs::path(f.out("seq")) / name));
    CHECK_FALSE(fs::exists(fs::path(f.out("seq")) / "frame-00003.png"));
}

TEST_CASE("bhm render --video says clearly when ffmpeg is missing") {
    Fixture f;
    // A PATH without ffmpeg (the test machine may or may not have one).
    const auto r = run(kExperiment + " --replay " + f.replay_path + " --video " + f.out("v.mp4"),
                       "PATH=" + f.dir.string());
    CHECK(r.status == 1);
    CHECK(r.output.find("needs ffmpeg on PATH") != std::string::npos);
    CHECK_FALSE(fs::exists(f.out("v.mp4")));
}

TEST_CASE("bhm render --video pipes raw frames to ffmpeg and moves the file into place") {
    Fixture f;
    // A stand-in ffmpeg that stores what it reads in the file named last; and one that fails.
    const fs::path bin = f.dir / "bin";
    fs::create_directories(bin);
    const auto script = [&](const std::string& name, const std::string& body) {
        const fs::path path = bin / name / "ffmpeg";
        fs::create_directories(path.parent_path());
        std::FILE* out = std::fopen(path.c_str(), "w");
        REQUIRE(out != nullptr);
        std::fputs(("#!/bin/sh\n" + body).c_str(), out);
        std::fclose(out);
        fs::permissions(path, fs::perms::owner_all);
        return "PATH=" + path.parent_path().string() + ":/usr/bin:/bin";
    };
    const std::string good = script("good", "for a; do out=\"$a\"; done\ncat > \"$out\"\n");
    // Its ffprobe counts the 4 frames sent: the file is then checked, not decoded.
    const fs::path probe = bin / "good" / "ffprobe";
    std::FILE* probe_file = std::fopen(probe.c_str(), "w");
    REQUIRE(probe_file != nullptr);
    std::fputs("#!/bin/sh\necho 4\n", probe_file);
    std::fclose(probe_file);
    fs::permissions(probe, fs::perms::owner_all);
    auto r = run(kExperiment + " --replay " + f.replay_path + " --video " + f.out("v.mp4") +
                     " --frames 4 --size 64x48 --fps 12",
                 good);
    CHECK(r.status == 0);
    CHECK(r.output.find("4 frames at 12 fps") != std::string::npos);
    REQUIRE(fs::exists(f.out("v.mp4")));
    CHECK(fs::file_size(f.out("v.mp4")) == 4u * 64u * 48u * 4u);  // RGBA frames, nothing else
    CHECK_FALSE(fs::exists(f.out("v.mp4.tmp.mp4")));

    const std::string bad = script("bad", "cat > /dev/null\nexit 1\n");
    r = run(kExperiment + " --replay " + f.replay_path + " --video " + f.out("w.mp4") +
                " --frames 2 --size 64x48",
            bad);
    CHECK(r.status == 1);
    CHECK(r.output.find("ffmpeg failed") != std::string::npos);
    CHECK_FALSE(fs::exists(f.out("w.mp4")));
    CHECK_FALSE(fs::exists(f.out("w.mp4.tmp.mp4")));
}

TEST_CASE("bhm render refuses bad input with one line naming the file or option") {
    Fixture f;
    const std::string base = kExperiment + " --body " + f.body_path + " --out " + f.out("x.png");
    auto r = run(base + " --size 10x10");
    CHECK(r.status == 2);
    CHECK(r.output.find("--size wants WxH") != std::string::npos);
    r = run(base + " --view diagonal");
    CHECK(r.status == 2);
    CHECK(r.output.find("--view must be iso, front, top or side") != std::string::npos);
    r = run(base + " --color rainbow");
    CHECK(r.status == 2);
    r = run(kExperiment + " --out " + f.out("x.png"));
    CHECK(r.status == 2);
    CHECK(r.output.find("missing --body") != std::string::npos);
    r = run(base + " --time 0.5");
    CHECK(r.status == 2);
    CHECK(r.output.find("need --replay") != std::string::npos);
    r = run(kExperiment + " --body " + f.out("missing.json") + " --out " + f.out("x.png"));
    CHECK(r.status == 1);
    CHECK(r.output.find("missing.json") != std::string::npos);
    r = run(kExperiment + " --replay " + f.body_path + " --out " + f.out("x.png"));  // not a replay
    CHECK(r.status == 1);
    CHECK(r.output.find(f.body_path) != std::string::npos);
    r = run(kExperiment + " --replay " + f.replay_path + " --out " + f.out("x.png") + " --time 5");
    CHECK(r.status == 1);
    CHECK(r.output.find("after the replay's end") != std::string::npos);
    r = run(base.substr(0, base.find(" --out")) + " --out " + f.out("no/such/dir/x.png"));
    CHECK(r.status == 1);
    CHECK(r.output.find("x.png") != std::string::npos);
    CHECK_FALSE(fs::exists(f.out("x.png")));
}

TEST_CASE("experiment mapping: colours, the free end opposite the fixed face, translucent frame") {
    evo::Experiment e = evo::load_experiment(kExperiment);
    const auto marks = app::render_face_markings(e);  // x- fixed, all others free
    CHECK(marks[0] == render::FaceMarking::Fixed);
    CHECK(marks[1] == render::FaceMarking::Free);
    for (int f = 2; f < 6; ++f)
        CHECK(marks[static_cast<std::size_t>(f)] == render::FaceMarking::None);

    const auto colors = app::render_material_colors(e);
    REQUIRE(colors.size() == e.materials.size() + 1);
    CHECK(colors[1].r == doctest::Approx(e.materials[1].color[0]));
    CHECK(colors.back().a < 1.0f);

    // A one-voxel frame on every face: frame voxels take the translucent entry.
    e.boundary.enclosure_material = 1;
    e.boundary.enclosure_thickness = {1, 1, 1, 1, 1, 1};
    evo::Body body;
    body.size = e.workspace_size;
    body.cells.assign(static_cast<std::size_t>(body.cell_count()), 2);
    const auto spec = evo::make_body_spec(e, evo::apply_frame_and_overrides(e, body));
    const render::Scene scene = app::rest_scene(e, spec);
    const auto frame_index = static_cast<std::uint8_t>(e.materials.size() + 1);
    int frame = 0, inner = 0;
    for (int v = 0; v < scene.body.voxel_count(); ++v) {
        const auto c = scene.body.voxel_coords(v);
        const bool outer =
            c[0] == 0 || c[1] == 0 || c[2] == 0 || c[0] == 7 || c[1] == 5 || c[2] == 4;
        const auto m = scene.body.voxel_material[static_cast<std::size_t>(v)];
        CHECK(m == (outer ? frame_index : 2));
        (outer ? frame : inner)++;
    }
    CHECK(inner == 6 * 4 * 3);
    CHECK(frame == 8 * 6 * 5 - inner);
}

TEST_CASE("replay scenes: poses at the time, ghost beside, trail, displacement in voxel lengths") {
    Fixture f;
    const engine::Replay replay = engine::read_replay(f.replay_path);
    app::ReplaySceneOptions options;
    options.ghost = options.ghost_beside = options.trail = true;
    render::Scene scene = app::replay_scene(f.experiment, replay, 0.5, options);
    CHECK(scene.body.poses.time_s == doctest::Approx(0.5));
    CHECK(scene.ghost_poses.has_value());
    CHECK(scene.options.ghost_offset_m.y == doctest::Approx(0.07f));  // (6 + 1) voxels of 1 cm
    options.ghost_axis = 0;  // front view: beside along x, (8 + 1) voxels
    const render::Scene along_x = app::replay_scene(f.experiment, replay, 0.5, options);
    CHECK(along_x.options.ghost_offset_m.x == doctest::Approx(0.09f));
    CHECK(along_x.options.ghost_offset_m.y == 0.0f);
    CHECK(scene.options.com_trail_m.size() == 6);  // frames at 0, 0.1 ... 0.5
    app::apply_scalar_coloring(scene, app::ScalarColoring::Displacement, &replay.frames.front());
    // Voxels away from the free end moved 1 mm = 0.1 voxel.
    CHECK(scene.options.voxel_scalar[0] == doctest::Approx(0.1f).epsilon(1e-3));
    CHECK(scene.options.color_mode == render::ColorMode::Scalar);
    const auto range = app::replay_scalar_range(replay, app::ScalarColoring::Displacement);
    CHECK(range.max ==
          doctest::Approx(std::sqrt(0.2 * 0.2 + 0.4 * 0.4)).epsilon(1e-3));  // free end at 1 s

    // A huge finite value (3.4e38, a float's largest) in one voxel of one frame: the scales stay
    // finite, the displacement's clamped (it was +inf, the strain's "-inf to inf"; issue 41).
    engine::Replay huge = replay;
    huge.frames.back().position_m[0] = std::numeric_limits<float>::max();
    huge.frames.back().size_m[0] = std::numeric_limits<float>::max();
    for (const auto coloring : {app::ScalarColoring::Displacement, app::ScalarColoring::Strain}) {
        const auto r = app::replay_scalar_range(huge, coloring);
        INFO(r.min << " to " << r.max);
        CHECK(std::isfinite(r.min));
        CHECK(std::isfinite(r.max));
        CHECK(std::isfinite(r.max - r.min));
    }
    // The displacement, 3.4e40 voxel lengths in double, is clamped; the strain, beyond a float,
    // is left out of the scale (that voxel takes its end colour).
    CHECK(app::replay_scalar_range(huge, app::ScalarColoring::Displacement).max ==
          static_cast<float>(render::kMaxScaleMagnitude));
    CHECK(app::replay_scalar_range(huge, app::ScalarColoring::Strain).max < 1.0f);
    render::Scene at_end = app::replay_scene(f.experiment, huge, 1.0, options);
    for (const auto coloring : {app::ScalarColoring::Displacement, app::ScalarColoring::Strain}) {
        app::apply_scalar_coloring(at_end, coloring, &huge.frames.front());
        const auto& r = at_end.options.scalar_range;
        INFO(r.min << " to " << r.max);
        CHECK(std::isfinite(r.max - r.min));
    }

    engine::Replay wrong = replay;
    wrong.nx = 3;
    CHECK_THROWS_WITH(app::replay_scene(f.experiment, wrong, 0.0),
                      doctest::Contains("not the experiment's workspace"));
}
