#pragma once
// Exports: a screenshot of the 3D view at any size (rendered off-screen, not read from the
// window), a replay as a numbered PNG sequence, and the champion as VXA (VoxCAD) and body JSON.
#include <string>
#include <vector>

#include "app/gui/studio.hpp"
#include "render/image.hpp"

namespace bhm::app::gui {

class ViewRenderer;

//! The 3D view's scene and camera rendered at width x height.
render::Image render_view_image(const Studio& studio, ViewRenderer& renderer, int width,
                                int height);

//! Writes the 3D view at width x height to path (its folder created); the status line shows the
//! absolute path written.
bool export_screenshot(Studio& studio, ViewRenderer& renderer, const std::string& path, int width,
                       int height);
//! Where the next numbered screenshot goes (F12, or Save PNG with an empty path): beside the
//! Export panel's path, else in default_screenshots_dir(), as bhm-view-001.png, -002, ...
std::string next_screenshot_path(const Studio& studio);

//! Starts writing the shown replay as folder/frame_00000.png ... at fps; continue_frame_export
//! writes one frame per call (one per UI frame) until done.
bool start_frame_export(Studio& studio, const std::string& folder, int width, int height,
                        double fps);
void continue_frame_export(Studio& studio, ViewRenderer& renderer);
//! The same frames into a video through ffmpeg (as `bhm render --video`): .mp4 or .gif by the
//! path's ending; it replaces path only once ffmpeg's output is verified.
bool start_video_export(Studio& studio, const std::string& path, int width, int height,
                        double fps);

//! The caption burnt into exported frames at time t (render/caption.hpp, as `bhm render
//! --caption`): the experiment, the body ("champion 412, generation 37"), its fitness under the
//! experiment's measure over the whole simulation, and the time.
std::vector<std::string> export_caption_lines(const SimulatedBody& body, double t_s);

//! The shown body (the champion while following it) as VXA / body JSON.
bool export_champion_vxa(Studio& studio, const std::string& path);
bool export_champion_json(Studio& studio, const std::string& path);

}  // namespace bhm::app::gui
