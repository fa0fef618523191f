// bhm render --video / --gif with the real ffmpeg (scripts/setup.sh installs it): ffprobe reads
// back the frame count, frame rate and duration, and the caption is in the decoded pixels.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "app/cli/render_video.hpp"
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
const std::string kExperiment = kSource + "/assets/experiments/quick-demo.json";

using Result = test::ShellResult;

Result shell(const std::string& command) {
    return test::run_shell(command);
}

// "key=value" lines of ffprobe's default writer.
double probe(const std::string& file, const std::string& entries, const std::string& key) {
    const auto r = shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries " +
                         entries + " -of default=noprint_wrappers=1 " + file);
    REQUIRE_MESSAGE(r.status == 0, r.output);
    const auto at = r.output.find(key + "=");
    REQUIRE_MESSAGE(at != std::string::npos, r.output);
    return std::stod(r.output.substr(at + key.size() + 1));
}

// A 4 x 3 x 2 body whose replay bends its free end down over 1 s, 11 frames.
struct Fixture {
    fs::path dir = bhm::test::scratch_dir("ffmpeg");
    std::string body_path, replay_path;
    Fixture() {
        const auto experiment = evo::load_experiment(kExperiment);
        evo::Body body;
        body.size = {4, 3, 2};
        body.cells.assign(24, 1);
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
            for (int v = 0; v < view.voxel_count(); ++v)
                poses.position_m[3 * static_cast<std::size_t>(v) + 2] -=
                    static_cast<float>(0.003 * poses.time_s * view.voxel_coords(v)[0]);
            replay.frames.push_back(poses);
        }
        replay_path = (dir / "replay.bin").string();
        engine::write_replay(replay_path, replay);
    }
    ~Fixture() { fs::remove_all(dir); }
    std::string out(const std::string& name) const { return (dir / name).string(); }
};

// Pixels of the top-left 100 x 30 corner (where the caption box goes) darker than 110 and
// brighter than 170 in every channel.
struct Corner {
    int dark = 0, bright = 0;
};
Corner corner(const render::Image& image) {
    Corner c;
    for (int y = 0; y < 30 && y < image.height; ++y)
        for (int x = 0; x < 100 && x < image.width; ++x) {
            const auto* p = image.pixel(x, y);
            c.dark += p[0] < 110 && p[1] < 110 && p[2] < 110 ? 1 : 0;
            c.bright += p[0] > 170 && p[1] > 170 && p[2] > 170 ? 1 : 0;
        }
    return c;
}

}  // namespace

TEST_CASE("real ffmpeg: MP4 and GIF have every frame at the asked rate, with the caption") {
    REQUIRE_MESSAGE(app::find_on_path("ffmpeg").has_value(), "ffmpeg is not installed");
    REQUIRE_MESSAGE(app::find_on_path("ffprobe").has_value(), "ffprobe is not installed");
    Fixture f;
    const auto r = shell(kBhm + " render " + kExperiment + " --replay " + f.replay_path +
                         " --video " + f.out("v.mp4") + " --gif " + f.out("v.gif") +
                         " --fps 10 --size 200x120 --samples 1 --caption");
    REQUIRE_MESSAGE(r.status == 0, r.output);
    CHECK_FALSE(fs::exists(f.out("v.mp4.tmp.mp4")));
    for (const char* name : {"v.mp4", "v.gif"}) {
        const std::string file = f.out(name);
        CHECK(probe(file, "stream=nb_read_frames", "nb_read_frames") == 11);
        CHECK(probe(file, "stream=width", "width") == 200);
        CHECK(probe(file, "format=duration", "duration") == doctest::Approx(1.1).epsilon(0.02));
    }
    // The first decoded frame carries the caption; an uncaptioned one does not.
    REQUIRE(shell("ffmpeg -v error -y -i " + f.out("v.mp4") + " -frames:v 1 " + f.out("f0.png"))
                .status == 0);
    REQUIRE(shell(kBhm + " render " + kExperiment + " --replay " + f.replay_path + " --out " +
                  f.out("plain.png") + " --time 0 --size 200x120 --samples 1")
                .status == 0);
    const Corner captioned = corner(render::read_png(f.out("f0.png")));
    const Corner plain = corner(render::read_png(f.out("plain.png")));
    // The light background turns dark under the box, and white text dots sit on it.
    CHECK(plain.dark < 100);
    CHECK(captioned.dark > 1500);
    CHECK(captioned.bright > 30);

    // Default rate is the replay's own (10 frames per second here), and --frames resamples.
    const auto g = shell(kBhm + " render " + kExperiment + " --replay " + f.replay_path +
                         " --gif " + f.out("w.gif") + " --frames 6 --size 64x48 --samples 1");
    REQUIRE_MESSAGE(g.status == 0, g.output);
    CHECK(probe(f.out("w.gif"), "stream=nb_read_frames", "nb_read_frames") == 6);
}

TEST_CASE("a video that ffmpeg claims to have written is verified before it replaces the old one") {
    // A stand-in ffmpeg that drains the frames, says nothing and exits 0, leaving a file it
    // cut short (what a full disk did to the real one in the trailer, issue 26 N1) or a whole
    // video of other frames. Only the decode by ffprobe can tell.
    const Fixture f;
    const auto good = shell(kBhm + " render " + kExperiment + " --replay " + f.replay_path +
                            " --video " + f.out("v.mp4") + " --size 64x48 --samples 1");
    REQUIRE_MESSAGE(good.status == 0, good.output);
    const auto six = shell(kBhm + " render " + kExperiment + " --replay " + f.replay_path +
                           " --video " + f.out("six.mp4") + " --frames 6 --size 64x48 --samples 1");
    REQUIRE_MESSAGE(six.status == 0, six.output);
    const auto bytes = fs::file_size(f.out("v.mp4"));
    const fs::path fake_dir = f.dir / "fake-bin";
    fs::create_directories(fake_dir);
    struct Case {
        std::string what_it_leaves, expected;
    } cases[] = {
        {"head -c " + std::to_string(bytes * 2 / 3) + " " + f.out("v.mp4"),
         "is damaged (ffprobe: "},
        {"cat " + f.out("six.mp4"), "holds 6 frames, not the 11 sent"},
        {"true", "ffmpeg left an empty file"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.what_it_leaves);
        shell("printf '#!/bin/sh\\ncat >/dev/null\\nfor last; do :; done\\n" + c.what_it_leaves +
              " > \"$last\"\\nexit 0\\n' > " + (fake_dir / "ffmpeg").string() + " && chmod +x " +
              (fake_dir / "ffmpeg").string());
        fs::copy_file(f.out("v.mp4"), f.out("old.mp4"), fs::copy_options::overwrite_existing);
        const auto r = shell("PATH=" + fake_dir.string() + ":$PATH " + kBhm + " render " +
                             kExperiment + " --replay " + f.replay_path + " --video " +
                             f.out("v.mp4") + " --size 64x48 --samples 1");
        CHECK(r.status == 1);
        CHECK(r.output.find(f.out("v.mp4") + ": ") != std::string::npos);
        CHECK(r.output.find(c.expected) != std::string::npos);
        CHECK(r.output.find("the previous file is unchanged") != std::string::npos);
        CHECK(r.output.find("wrote") == std::string::npos);
        CHECK(shell("cmp " + f.out("v.mp4") + " " + f.out("old.mp4")).status == 0);
        CHECK_FALSE(fs::exists(f.out("v.mp4.tmp.mp4")));
    }
}
