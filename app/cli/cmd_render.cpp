// bhm render: a body at rest, or a replay at a time, as PNG (or a PNG sequence, or an MP4 through
// ffmpeg), drawn off-screen with OSMesa: no display needed. Scene building lives in
// app/cli/render_scene.hpp, drawing in render/.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/problem_report.hpp"
#include "app/cli/render_scene.hpp"
#include "app/cli/render_video.hpp"
#include "engine/io/staged_folder.hpp"
#include "engine/replay.hpp"
#include "evo/evaluate/replay_measures.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "render/caption.hpp"
#include "render/draw_list.hpp"
#include "render/offscreen.hpp"
#include "render/renderer.hpp"
#include "render/replay_view.hpp"

// OSMesa keeps a few hundred bytes per context after OSMesaDestroyContext; under BHM_SANITIZE
// LeakSanitizer would turn that into a failed exit status. The leak is Mesa's, not ours.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa.so\n";
}
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0";
}

namespace bhm::app {

namespace {

const char* const kSummary =
    "Draws BODY (framed by EXPERIMENT, at rest) or a replay of it, without a display, to:\n"
    "  --out shot.png                   one image (a replay: at --time, default its last frame)\n"
    "  --frames N --out-dir DIR         N images spread over the replay, frame-00000.png ...\n"
    "  --video out.mp4                  an H.264 video of the replay through ffmpeg (on PATH)\n"
    "  --gif out.gif                    an animated GIF of the replay through ffmpeg\n"
    "With --caption every image carries the time, the experiment's fitness so far and the\n"
    "bend angle so far (both from the replay, measured from the end of settling).\n"
    "The picture follows the paper's figures: muscle red, tissue blue, enclosure translucent,\n"
    "held voxels hatched green, the fixed workspace face green and the free one opposite it\n"
    "purple, a star on the (0,0,0) voxel.\n"
    "\n"
    "exit status: 0 ok, 1 invalid input or failure (every problem of the files printed as\n"
    "file:field: message), 2 usage error.";

struct Size {
    int width = 1280, height = 720;
};

Size parse_size(const std::string& text) {
    Size size;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%dx%d%c", &size.width, &size.height, &extra) != 2 ||
        size.width < 16 || size.height < 16 || size.width > 8192 || size.height > 8192)
        throw UsageError("--size wants WxH with each side in 16..8192, got '" + text + "'");
    return size;
}

std::string describe_time(double t) {
    char text[48];
    std::snprintf(text, sizeof text, "t = %.3f s", t);
    return text;
}

// The camera for the whole output: one framing for every frame, so sequences do not jump.
render::Camera output_camera(render::NamedView view, const render::DrawList& list,
                             const engine::Replay* replay, const render::Scene& scene, Size size) {
    render::Bounds bounds = list.bounds;
    if (replay) {
        const render::Bounds moving = render::replay_bounds(*replay);
        bounds.add(moving);
        if (scene.options.show_ghost && moving.valid) {
            render::Bounds shifted = moving;
            shifted.min += scene.options.ghost_offset_m;
            shifted.max += scene.options.ghost_offset_m;
            bounds.add(shifted);
        }
    }
    return render::named_view(view, bounds,
                              static_cast<float>(size.width) / static_cast<float>(size.height));
}

int render_command(ArgParser& args) {
    const std::string experiment_path = args.positionals().at(0);
    const Size size = parse_size(args.get("--size", "1280x720"));
    const auto view = render::parse_named_view(args.get("--view", "iso"));
    if (!view)
        throw UsageError("--view must be iso, front, top or side, got '" + args.get("--view") +
                         "'");
    ScalarColoring coloring = ScalarColoring::Material;
    try {
        coloring = parse_scalar_coloring(args.get("--color", "material"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--color: ") + e.what());
    }
    const long long section = args.get_int("--section", -1);
    if (args.has("--section") && section < 0)
        throw UsageError("--section must be a lattice y >= 0");
    const long long samples = args.get_int("--samples", 4);
    if (samples < 1 || samples > 16) throw UsageError("--samples must be in 1..16");
    const long long phase_seed = args.get_int("--phase-seed", 0);
    if (phase_seed < 0) throw UsageError("--phase-seed must be >= 0");
    const std::string ghost = args.get("--ghost", "");
    if (args.has("--ghost") && ghost != "over" && ghost != "beside")
        throw UsageError("--ghost must be over or beside, got '" + ghost + "'");

    const bool has_replay = args.has("--replay");
    const bool animation = args.has("--video") || args.has("--gif");
    const bool sequence = args.has("--frames") && !animation;
    if (!args.has("--body") && !has_replay)
        throw UsageError("missing --body BODY.json (or --replay REPLAY.bin)");
    if ((args.has("--time") || args.has("--frames") || animation || args.has("--ghost") ||
         args.has("--trail")) &&
        !has_replay)
        throw UsageError(
            "--time, --frames, --video, --gif, --ghost and --trail need --replay REPLAY.bin");
    if (sequence && !args.has("--out-dir")) throw UsageError("--frames N needs --out-dir DIR");
    if (!sequence && !animation && !args.has("--out")) throw UsageError("missing --out FILE.png");
    const long long frame_count = args.get_int("--frames", 0);
    if (args.has("--frames") && (frame_count < 1 || frame_count > 100000))
        throw UsageError("--frames must be in 1..100000");
    if (args.has("--time") && args.get_double("--time", 0.0) < 0.0)
        throw UsageError("--time must be >= 0");

    // Inputs: every problem of both files before giving up.
    evo::Experiment experiment;
    evo::Body body;
    bool body_ok = false;
    try {
        auto loaded = evo::load_experiment_and_body(experiment_path, args.get("--body", ""));
        say_library_warnings(loaded.experiment);
        experiment = std::move(loaded.experiment);
        body_ok = loaded.body.has_value();
        if (body_ok) body = std::move(*loaded.body);
    } catch (const evo::ValidationError& e) {
        return report_problems(e.problems);
    }

    std::optional<engine::BodySpec> spec;
    if (body_ok) {
        try {
            spec = evo::make_body_spec(experiment, evo::apply_frame_and_overrides(experiment, body),
                                       static_cast<std::uint64_t>(phase_seed));
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(args.get("--body") + ": cannot build the body: " + e.what());
        }
    }
    if (coloring == ScalarColoring::Phase && !spec)
        throw UsageError("--color phase needs --body BODY.json");

    std::optional<engine::Replay> replay;
    if (has_replay) {
        replay = engine::read_replay(args.get("--replay"));  // throws naming the file
        if (replay->frames.empty())
            throw std::runtime_error(args.get("--replay") + ": the replay has no frames");
        const auto& w = experiment.workspace_size;
        if (replay->nx != w[0] || replay->ny != w[1] || replay->nz != w[2])
            throw std::runtime_error(args.get("--replay") + ": lattice " +
                                     std::to_string(replay->nx) + "x" + std::to_string(replay->ny) +
                                     "x" + std::to_string(replay->nz) + " is not the workspace " +
                                     std::to_string(w[0]) + "x" + std::to_string(w[1]) + "x" +
                                     std::to_string(w[2]) + " of " + experiment_path);
    }
    const double first_s = replay ? replay->frames.front().time_s : 0.0;
    const double last_s = replay ? replay->frames.back().time_s : 0.0;
    if (args.has("--time") && args.get_double("--time", 0.0) > last_s + 1e-9)
        throw std::runtime_error(args.get("--replay") + ": --time " + args.get("--time") +
                                 " is after the replay's end at " + describe_time(last_s));

    ReplaySceneOptions replay_options;
    replay_options.ghost = args.has("--ghost");
    replay_options.ghost_beside = ghost == "beside";
    // Beside means across the line of sight: along x when looking along y (front view).
    replay_options.ghost_axis = *view == render::NamedView::Front ? 0 : 1;
    replay_options.trail = args.has("--trail");
    replay_options.interpolate = !args.has("--nearest");
    const std::vector<float>* phases = spec ? &spec->phase_rad : nullptr;
    // One colour scale for the whole output, so frames of a sequence compare.
    std::optional<render::ScalarRange> range;
    if (replay && coloring != ScalarColoring::Material)
        range = replay_scalar_range(*replay, coloring);
    const auto scene_at = [&](double t) {
        render::Scene scene = replay ? replay_scene(experiment, *replay, t, replay_options)
                                     : rest_scene(experiment, *spec);
        scene.options.section_y = static_cast<int>(section);
        apply_scalar_coloring(scene, coloring, replay ? &replay->frames.front() : nullptr, phases);
        if (range) scene.options.scalar_range = *range;
        return scene;
    };

    if (coloring != ScalarColoring::Material) {
        const render::ScalarRange shown = range ? *range : scene_at(first_s).options.scalar_range;
        const char* unit = coloring == ScalarColoring::Displacement ? " voxel lengths"
                           : coloring == ScalarColoring::Phase      ? " rad"
                                                                    : " (volume change)";
        std::cout << "colour scale: " << args.get("--color") << " " << shown.min << " to "
                  << shown.max << unit << "\n";
    }
    render::OffscreenTarget target(size.width, size.height, static_cast<int>(samples));
    render::Renderer renderer;
    const render::Scene first_scene = scene_at(first_s);
    const render::Camera camera = output_camera(*view, render::build_draw_list(first_scene),
                                                replay ? &*replay : nullptr, first_scene, size);
    // Caption: the measures so far at the last recorded frame at or before t.
    std::vector<std::array<double, evo::kMeasureCount>> measures;
    if (args.has("--caption") && replay) measures = evo::replay_measures(experiment, *replay);
    const auto caption_lines = [&](double t) {
        std::vector<std::string> lines;
        if (!replay) return std::vector<std::string>{"at rest"};
        lines.push_back(describe_time(t));
        std::size_t frame = 0;
        while (frame + 1 < replay->frames.size() && replay->frames[frame + 1].time_s <= t + 1e-9)
            ++frame;
        const auto& m = measures[frame];
        char text[96];
        const auto measure = static_cast<std::size_t>(experiment.fitness.measure);
        std::snprintf(text, sizeof text, "fitness %.3f (%s)", m[measure],
                      evo::kFitnessNames[measure]);
        lines.push_back(text);
        std::snprintf(text, sizeof text, "bend %.1f deg",
                      m[static_cast<std::size_t>(evo::FitnessMeasure::BendAngleDeg)]);
        lines.push_back(text);
        return lines;
    };
    render::Image image;
    const auto draw = [&](double t) {
        target.bind();
        renderer.draw(render::build_draw_list(scene_at(t)), camera, size.width, size.height);
        target.read_image(image);
        if (args.has("--caption"))
            render::draw_caption(image, caption_lines(t), render::caption_scale_for(size.height));
    };
    // N times spread evenly over the replay, first and last included.
    const auto time_of = [&](long long i, long long n) {
        return n <= 1 ? last_s
                      : first_s + (last_s - first_s) * static_cast<double>(i) /
                                      static_cast<double>(n - 1);
    };

    if (args.has("--out")) {
        const double t = args.has("--time") ? args.get_double("--time", 0.0) : last_s;
        draw(t);
        render::write_png(args.get("--out"), image);
        std::cout << "wrote " << args.get("--out") << " (" << size.width << "x" << size.height
                  << ", " << render::named_view_name(*view)
                  << (replay ? ", " + describe_time(t) : std::string(", at rest")) << ")\n";
    }
    if (sequence) {
        const std::filesystem::path dir(args.get("--out-dir"));
        // The frames are staged and swapped in whole (engine/io/staged_folder.hpp): a kill or a
        // failed write leaves the old sequence, never old frames among new ones (issue 41 R5).
        engine::StagedFolder staged(dir.string(), [](const std::string& name) {
            return name.rfind("frame-", 0) == 0 && name.size() > 4 &&
                   name.compare(name.size() - 4, 4, ".png") == 0;
        });
        for (long long i = 0; i < frame_count; ++i) {
            draw(time_of(i, frame_count));
            char name[32];
            std::snprintf(name, sizeof name, "frame-%05lld.png", i);
            try {
                render::write_png(staged.file(name), image);
            } catch (const std::runtime_error& e) {
                throw std::runtime_error(staged.as_final(e.what()));
            }
        }
        staged.commit();
        std::cout << "wrote " << frame_count << " frames to " << dir.string() << " ("
                  << describe_time(first_s) << " to " << describe_time(last_s) << ")\n";
    }
    if (animation) {
        const long long n =
            args.has("--frames") ? frame_count : static_cast<long long>(replay->frames.size());
        // Real time by default: the replay's own frame rate.
        const double recorded_fps =
            last_s > first_s ? static_cast<double>(n - 1) / (last_s - first_s) : 30.0;
        const double fps = args.get_double("--fps", recorded_fps);
        if (!(fps > 0.0) || fps > 1000.0) throw UsageError("--fps must be in (0, 1000]");
        // Both outputs from one pass over the frames when both are asked for.
        std::vector<std::unique_ptr<VideoWriter>> writers;
        std::vector<std::string> paths;
        if (args.has("--video")) {
            paths.push_back(args.get("--video"));
            writers.push_back(std::make_unique<VideoWriter>(paths.back(), size.width, size.height,
                                                            fps, VideoFormat::Mp4));
        }
        if (args.has("--gif")) {
            paths.push_back(args.get("--gif"));
            writers.push_back(std::make_unique<VideoWriter>(paths.back(), size.width, size.height,
                                                            fps, VideoFormat::Gif));
        }
        for (long long i = 0; i < n; ++i) {
            draw(time_of(i, n));
            for (auto& w : writers)
                w->write(image);
        }
        // Every video verified before the first replaces anything: --video and --gif together
        // give both new files or neither.
        for (auto& w : writers)
            w->finish();
        for (std::size_t w = 0; w < writers.size(); ++w) {
            writers[w]->commit();
            std::cout << "wrote " << paths[w] << " (" << n << " frames at " << fps << " fps)\n";
        }
    }
    return 0;
}

}  // namespace

int cmd_render(const Args& args) {
    ArgParser parser("render", "EXPERIMENT.json (--body BODY.json | --replay REPLAY.bin) [OPTIONS]",
                     kSummary);
    parser
        .positional("EXPERIMENT.json",
                    "the experiment: workspace, materials, boundary faces, enclosure")
        .option("--body", "BODY.json", "the body to draw (at rest unless --replay)")
        .option("--replay", "REPLAY.bin", "a recorded simulation (bhm simulate's replay.bin)")
        .option("--out", "FILE.png", "write one image", PathRole::OutputFile)
        .option("--time", "T", "replay time in seconds for --out (default: the last frame)")
        .flag("--nearest", "show the last recorded frame at or before T instead of blending frames")
        .option("--frames", "N",
                "with --out-dir: N images spread over the replay; with --video/--gif: N frames")
        .option("--out-dir", "DIR", "folder for --frames (frame-00000.png, ...), replaced whole",
                PathRole::OutputDir)
        .option("--video", "FILE.mp4", "an H.264 video of the replay (needs ffmpeg on PATH)",
                PathRole::OutputFile)
        .option("--gif", "FILE.gif", "an animated GIF of the replay (needs ffmpeg on PATH)",
                PathRole::OutputFile)
        .option("--fps", "F", "video frame rate (default: the replay's, i.e. real time)")
        .flag("--caption", "write the time, fitness and bend angle so far into every image")
        .option("--size", "WxH", "image size in pixels (default 1280x720)")
        .option("--view", "VIEW", "iso (default), front (from +y), top or side (from +x)")
        .option("--section", "Y",
                "hide voxels with lattice y > Y (a front section, paper Figure 13)")
        .option("--color", "BY",
                "material (default), displacement (from t = 0), strain (volumetric) or phase")
        .option("--phase-seed", "N",
                "seed of random actuation phases, as given to bhm simulate (default 0)")
        .option("--ghost", "WHERE",
                "draw the t = 0 state translucent, 'over' the body or 'beside' it")
        .flag("--trail", "draw the centre-of-mass trail up to the time shown")
        .option("--samples", "N", "anti-aliasing samples per pixel, 1..16 (default 4)");
    return run_command(parser, args, render_command);
}

}  // namespace bhm::app
