// The Export panel: screenshot of the 3D view at any size, a replay as a PNG sequence, the
// champion (or the body shown) as VXA and body JSON, its controller (saved, or another one
// driving the body shown), its surface mesh (STL/OBJ, at rest or deformed at the replay time)
// and its replay as a ParaView series, as `bhm export` writes them.
#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/gui/actions/controller_actions.hpp"
#include "app/gui/actions/export_actions.hpp"
#include "app/gui/actions/export_geometry.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

void path_field(Studio& s, const char* id, std::string& value) {
    char buffer[1024];
    std::snprintf(buffer, sizeof buffer, "%s", value.c_str());
    ImGui::SetNextItemWidth(-1.0f);
    if (ImGui::InputText(id, buffer, sizeof buffer)) value = buffer;
    record_widget(s, id + 2);
}

void hint(const char* text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

void size_fields(const char* id, int& width, int& height) {
    int size[2] = {width, height};
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 9.0f);
    if (ImGui::InputInt2(id, size)) {
        width = size[0];
        height = size[1];
    }
    ImGui::SameLine();
    ImGui::TextDisabled("px");
}

}  // namespace

void draw_export_panel(Studio& s, ViewRenderer& renderer) {
    auto& x = s.exports;
    section_title("Screenshot of the 3D view (F12)");
    path_field(s, "##screenshot path", x.screenshot_path);
    size_fields("size##shot", x.screenshot_width, x.screenshot_height);
    ImGui::SameLine();
    if (tracked_button(s, "Save PNG"))
        export_screenshot(s, renderer,
                          x.screenshot_path.empty() ? next_screenshot_path(s) : x.screenshot_path,
                          x.screenshot_width, x.screenshot_height);
    hint(
        "rendered off-screen at that size, with the view's camera; an empty path numbers them "
        "in the screenshots folder, F12 numbers them beside the path");

    section_title("Replay as a frame sequence");
    path_field(s, "##frames folder", x.frames_folder);
    size_fields("size##frames", x.frames_width, x.frames_height);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 5.0f);
    ImGui::InputDouble("frames/s", &x.frames_fps, 0.0, 0.0, "%.4g");
    ImGui::SameLine();
    if (x.frame_job.active) {
        ImGui::ProgressBar(float(x.frame_job.next) / float(std::max(1, x.frame_job.total)),
                           ImVec2(-ImGui::GetFontSize() * 5.0f, 0.0f));
        ImGui::SameLine();
        if (tracked_button(s, "Cancel")) x.frame_job.active = false;
    } else {
        ImGui::BeginDisabled(!s.bodies.shown);
        if (tracked_button(s, "Write frames"))
            start_frame_export(s, x.frames_folder, x.frames_width, x.frames_height, x.frames_fps);
        ImGui::EndDisabled();
    }
    ImGui::SameLine();
    ImGui::Checkbox("caption", &x.caption);
    record_widget(s, "caption");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "burn the experiment, the body and its generation, its fitness and the "
            "time into every frame (and video)");
    hint("frame_00000.png ... over the whole simulated time");
    path_field(s, "##video path", x.video_path);
    ImGui::BeginDisabled(!s.bodies.shown || x.frame_job.active);
    if (tracked_button(s, "Write video"))
        start_video_export(s, x.video_path, x.frames_width, x.frames_height, x.frames_fps);
    ImGui::EndDisabled();
    hint("the same frames as an .mp4 (H.264) or an animated .gif through ffmpeg");

    section_title("Champion (or the body shown)");
    path_field(s, "##vxa path", x.champion_vxa_path);
    if (tracked_button(s, "Save VXA")) export_champion_vxa(s, x.champion_vxa_path);
    ImGui::SameLine();
    ImGui::TextDisabled("VoxCAD / Voxelyze 1.0");
    path_field(s, "##json path", x.champion_json_path);
    if (tracked_button(s, "Save body JSON")) export_champion_json(s, x.champion_json_path);
    ImGui::SameLine();
    ImGui::TextDisabled("bhm body file");

    section_title("Surface mesh and ParaView");
    path_field(s, "##mesh path", x.mesh_path);
    if (tracked_button(s, "Save mesh")) export_mesh(s, x.mesh_path, x.mesh_deformed);
    ImGui::SameLine();
    ImGui::Checkbox("deformed at the replay time", &x.mesh_deformed);
    record_widget(s, "mesh deformed");
    hint("closed surface in metres: .stl, or .obj with a .mtl (a group per material)");
    path_field(s, "##vtk folder", x.vtk_folder);
    ImGui::BeginDisabled(!s.bodies.shown);
    if (tracked_button(s, "Write ParaView series")) export_vtk_series(s, x.vtk_folder);
    ImGui::EndDisabled();
    hint("series.pvd, one .vtu per replay frame and the centre of mass path (.vtp)");

    // Last, so the geometry exports above keep their place in a short tile.
    section_title("Controller (issue 44)");
    path_field(s, "##controller path", x.controller_path);
    ImGui::BeginDisabled(!s.bodies.shown);
    if (tracked_button(s, "Save controller JSON")) export_shown_controller(s, x.controller_path);
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("the shown champion's controller CPPN");
    path_field(s, "##controller item", x.controller_item);
    ImGui::BeginDisabled(!s.bodies.shown || x.controller_item.empty());
    if (tracked_button(s, "Drive the body shown")) drive_shown_body(s, x.controller_item);
    ImGui::EndDisabled();
    hint(
        "replay the body shown under a controller file, a run folder's champion controller, or "
        "uniform, wave, random[:SEED]");
}

}  // namespace bhm::app::gui
