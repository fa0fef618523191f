#include "app/gui/actions/export_actions.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/cli/render_video.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "app/gui/view/renderer.hpp"
#include "app/gui/view/scene.hpp"
#include "app/gui/view/viewport.hpp"
#include "app/gui/widgets/ui_widgets.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/formats/vxa.hpp"
#include "render/caption.hpp"

namespace bhm::app::gui {

namespace {

constexpr int kMaxExportSide = 16384;

bool check_size(Studio& s, int width, int height) {
    if (width < 1 || height < 1 || width > kMaxExportSide || height > kMaxExportSide) {
        set_status(s,
                   "export: size " + std::to_string(width) + "x" + std::to_string(height) +
                       " is outside 1..16384 pixels",
                   true);
        return false;
    }
    return true;
}

const evo::Body* body_to_export(const Studio& s, const evo::Experiment** experiment) {
    if (s.bodies.shown && s.bodies.shown->framed_body) {
        *experiment = &s.bodies.shown->experiment;
        return s.bodies.shown->framed_body.get();
    }
    if (s.run.snapshot && s.run.snapshot->has_champion && s.run.snapshot->champion.body) {
        *experiment = &s.run.snapshot->experiment;
        return s.run.snapshot->champion.body.get();
    }
    return nullptr;
}

}  // namespace

void make_parent_folder(const std::string& path) {
    const auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
}

render::Image render_view_image(const Studio& s, ViewRenderer& renderer, int width, int height) {
    const render::DrawList list = build_view_draw_list(s);
    return renderer.draw_to_image(list, s.view.camera, width, height, 4);
}

bool export_screenshot(Studio& s, ViewRenderer& renderer, const std::string& path, int width,
                       int height) {
    if (!check_size(s, width, height)) return false;
    try {
        const std::filesystem::path absolute(absolute_path(path));
        if (absolute.has_parent_path()) std::filesystem::create_directories(absolute.parent_path());
        render::write_png(absolute.string(), render_view_image(s, renderer, width, height));
        if (width * height > 4096 * 4096) renderer.release_export_buffer();
        set_status(s, "screenshot written: " + absolute.string() + " (" + std::to_string(width) +
                          "x" + std::to_string(height) + ")");
        return true;
    } catch (const std::exception& e) {
        set_status(s, std::string("screenshot: ") + e.what(), true);
        return false;
    }
}

std::string next_screenshot_path(const Studio& s) {
    const std::string& typed = s.exports.screenshot_path;
    return next_numbered_path(
        typed.empty() ? (std::filesystem::path(default_screenshots_dir()) / "bhm-view.png").string()
                      : typed);
}

bool start_video_export(Studio& s, const std::string& path, int width, int height, double fps) {
    const auto ends = [&](const char* suffix) {
        const std::string x(suffix);
        return path.size() >= x.size() && path.compare(path.size() - x.size(), x.size(), x) == 0;
    };
    const bool gif = ends(".gif") || ends(".GIF");
    if (!gif && !ends(".mp4") && !ends(".MP4")) {
        set_status(s, "video: the file name ends in .mp4 or .gif, got '" + path + "'", true);
        return false;
    }
    const auto folder = std::filesystem::path(path).parent_path();
    if (!start_frame_export(s, folder.empty() ? "." : folder.string(), width, height, fps))
        return false;
    auto& job = s.exports.frame_job;
    try {
        job.video = std::make_shared<VideoWriter>(path, width, height, fps,
                                                  gif ? VideoFormat::Gif : VideoFormat::Mp4);
    } catch (const std::exception& e) {
        job = {};
        set_status(s, std::string("video: ") + e.what(), true);
        return false;
    }
    job.video_path = std::filesystem::absolute(path).string();
    set_status(s, "writing " + std::to_string(job.total) + " frames to " + job.video_path);
    return true;
}

bool start_frame_export(Studio& s, const std::string& folder, int width, int height, double fps) {
    if (!s.bodies.shown || s.bodies.shown->replay.frames.empty()) {
        set_status(s, "frame export: no simulated body to export", true);
        return false;
    }
    if (!check_size(s, width, height)) return false;
    if (!(fps > 0.0 && fps <= 1000.0)) {
        set_status(s, "frame export: frames per second must be in (0, 1000]", true);
        return false;
    }
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) {
        set_status(s, folder + ": cannot create the folder: " + ec.message(), true);
        return false;
    }
    auto& job = s.exports.frame_job;
    job = {};
    job.active = true;
    job.folder = folder;
    job.width = width;
    job.height = height;
    job.fps = fps;
    job.total = static_cast<int>(std::floor(s.clock.duration_s * fps + 1e-6)) + 1;
    set_status(s, "writing " + std::to_string(job.total) + " frames to " + folder);
    return true;
}

std::vector<std::string> export_caption_lines(const SimulatedBody& b, double t_s) {
    std::string label;  // the dot font has no '#'
    for (char c : b.label)
        if (c != '#') label += c;
    const auto measure = b.experiment.fitness.measure;
    char fitness[96], time[48];
    std::snprintf(fitness, sizeof fitness, "fitness %.4g %s (%s)", b.fitness,
                  fitness_unit(measure), evo::kFitnessNames[static_cast<std::size_t>(measure)]);
    std::snprintf(time, sizeof time, "t = %.3f s", t_s);
    return {b.experiment.name, label, fitness, time};
}

void continue_frame_export(Studio& s, ViewRenderer& renderer) {
    auto& job = s.exports.frame_job;
    if (!job.active) {
        job.video.reset();  // cancelled: ffmpeg is stopped, its temporary removed
        return;
    }
    if (!s.bodies.shown) {
        job.active = false;
        set_status(s, "frame export stopped: the body is gone", true);
        return;
    }
    const double t = job.next / job.fps;
    render::Scene scene = simulation_scene(*s.bodies.shown, t, s.view);
    const render::DrawList list = render::build_draw_list(scene);
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%05d.png", job.next);
    try {
        render::Image image =
            renderer.draw_to_image(list, s.view.camera, job.width, job.height, 4);
        if (s.exports.caption)
            render::draw_caption(image, export_caption_lines(*s.bodies.shown, t),
                                 render::caption_scale_for(job.height));
        if (job.video)
            job.video->write(image);
        else
            render::write_png(job.folder + name, image);
        if (++job.next >= job.total && job.video) {
            job.video->finish();
            job.video->commit();
        }
    } catch (const std::exception& e) {
        job.active = false;
        job.video.reset();
        set_status(s, std::string(job.video_path.empty() ? "frame export: " : "video: ") +
                          e.what(),
                   true);
        return;
    }
    if (job.next >= job.total) {
        job.active = false;
        set_status(s, job.video ? "video written (" + std::to_string(job.total) +
                                      " frames): " + job.video_path
                                : "wrote " + std::to_string(job.total) + " frames to " +
                                      job.folder);
        job.video.reset();
    }
}

bool export_champion_vxa(Studio& s, const std::string& path) {
    const evo::Experiment* experiment = nullptr;
    const evo::Body* body = body_to_export(s, &experiment);
    if (!body) {
        set_status(s, "export: no champion or simulated body yet", true);
        return false;
    }
    try {
        make_parent_folder(path);  // the defaults' folder in the data folder may not exist yet
        evo::save_vxa(path, *experiment, *body);
        set_status(s, "VXA written: " + path);
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

bool export_champion_json(Studio& s, const std::string& path) {
    const evo::Experiment* experiment = nullptr;
    const evo::Body* body = body_to_export(s, &experiment);
    if (!body) {
        set_status(s, "export: no champion or simulated body yet", true);
        return false;
    }
    try {
        make_parent_folder(path);  // the defaults' folder in the data folder may not exist yet
        evo::save_body(path, *body);
        set_status(s, "body JSON written: " + path);
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

}  // namespace bhm::app::gui
