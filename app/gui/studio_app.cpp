#include "app/gui/studio_app.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <glad/gl.h>

#include <imgui.h>

#include "app/gui/actions/export_actions.hpp"
#include "app/gui/actions/key_bindings.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/file_dialog_widget.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/tile_layout.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

// The tiles draw no background of their own: the runners clear the whole framebuffer to the
// window colour first (ui_clear_color). On a software rasterizer that saves blending a full
// window of pixels every frame.
constexpr ImGuiWindowFlags kTileFlags =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBringToFrontOnFocus |
    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground;

// Font files from Debian's fonts-dejavu-core; ImGui's built-in font when absent.
constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Places a tile; returns its size after Begin (the user may have dragged an edge this frame).
ImVec2 begin_tile(const char* name, ImVec2 pos, ImVec2 size, ImGuiWindowFlags extra = 0) {
    ImGui::SetNextWindowPos(pos, ImGuiCond_Always);
    ImGui::SetNextWindowSize(size, ImGuiCond_Always);
    ImGui::Begin(name, nullptr, kTileFlags | extra);
    return ImGui::GetWindowSize();
}

// A thin strip over an inner edge: dragging it moves the edge (the settings remember it).
void splitter(Studio& s, const char* name, ImVec2 pos, ImVec2 size, Splitter which, float width,
              float height) {
    const bool vertical = which == Splitter::Left || which == Splitter::Right;
    ImGui::SetNextWindowPos(pos, ImGuiCond_Always);
    ImGui::SetNextWindowSize(size, ImGuiCond_Always);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
    ImGui::Begin(name, nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoBackground |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    area_button("##edge", size);
    record_widget(s, name);
    if (ImGui::IsItemHovered() || ImGui::IsItemActive()) {
        ImGui::SetMouseCursor(vertical ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
        ImGui::GetWindowDrawList()->AddRectFilled(
            ImGui::GetItemRectMin(), ImGui::GetItemRectMax(),
            ImGui::GetColorU32(ImGui::IsItemActive() ? ImGuiCol_SeparatorActive
                                                     : ImGuiCol_SeparatorHovered));
    } else {
        // A grip at rest, so the edge can be found before the pointer happens on it: three dots
        // across the middle of the strip (the edges were invisible, issue 25 item 7).
        const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
        const ImVec2 mid((lo.x + hi.x) * 0.5f, (lo.y + hi.y) * 0.5f);
        const ImU32 colour = ImGui::GetColorU32(ImGuiCol_Separator);
        for (int k = -1; k <= 1; ++k) {
            const ImVec2 at = vertical ? ImVec2(mid.x, mid.y + 5.0f * k)
                                       : ImVec2(mid.x + 5.0f * k, mid.y);
            ImGui::GetWindowDrawList()->AddCircleFilled(at, 1.5f, colour);
        }
    }
    if (ImGui::IsItemActive()) {
        const ImVec2 d = ImGui::GetIO().MouseDelta;
        const float delta = vertical ? d.x : d.y;
        if (delta != 0.0f)
            drag_splitter(s.settings.layout, s.ui.tiles, which, delta, width, height);
    }
    ImGui::End();
    ImGui::PopStyleVar(3);
}

// The left column's tabs: Experiment, Constraints, Files, Export.
void draw_design_tabs(Studio& s, ViewRenderer& renderer) {
    if (!ImGui::BeginTabBar("design tabs")) return;
    const bool experiment_open = ImGui::BeginTabItem("Experiment");
    record_widget(s, "tab Experiment");
    if (experiment_open) {
        draw_experiment_panel(s);
        ImGui::EndTabItem();
    }
    const bool constraints_open = ImGui::BeginTabItem("Constraints");
    record_widget(s, "tab Constraints");
    if (constraints_open) {
        draw_constraints_panel(s);
        ImGui::EndTabItem();
    }
    const bool files_open = ImGui::BeginTabItem("Files");
    record_widget(s, "tab Files");
    if (files_open) {
        draw_files_panel(s);
        ImGui::EndTabItem();
    }
    const bool export_open = ImGui::BeginTabItem("Export");
    record_widget(s, "tab Export");
    if (export_open) {
        draw_export_panel(s, renderer);
        ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
}

// Records the current window's rectangle under `name`.
void record_widget_window(Studio& s, const std::string& name) {
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    s.ui.widgets[name] = WidgetRect{{pos.x, pos.y}, {pos.x + size.x, pos.y + size.y}, s.ui.frame};
}

}  // namespace

std::string apply_studio_style(float scale) {
    ImGuiIO& io = ImGui::GetIO();
    ImGuiStyle& style = ImGui::GetStyle();
    ImGui::StyleColorsLight(&style);
    style.WindowRounding = 0.0f;
    style.FrameRounding = 3.0f;
    style.GrabRounding = 3.0f;
    style.TabRounding = 3.0f;
    style.WindowBorderSize = 1.0f;
    style.FrameBorderSize = 1.0f;
    style.WindowPadding = ImVec2(8.0f, 6.0f);
    style.ItemSpacing = ImVec2(6.0f, 5.0f);
    style.ScrollbarSize = 12.0f;
    ImVec4* c = style.Colors;
    c[ImGuiCol_WindowBg] = ImVec4(0.965f, 0.968f, 0.975f, 1.0f);
    c[ImGuiCol_TitleBg] = ImVec4(0.86f, 0.88f, 0.91f, 1.0f);
    c[ImGuiCol_TitleBgActive] = ImVec4(0.80f, 0.84f, 0.90f, 1.0f);
    c[ImGuiCol_Header] = ImVec4(0.80f, 0.85f, 0.93f, 1.0f);
    c[ImGuiCol_HeaderHovered] = ImVec4(0.72f, 0.80f, 0.92f, 1.0f);
    c[ImGuiCol_HeaderActive] = ImVec4(0.20f, 0.38f, 0.66f, 1.0f);
    c[ImGuiCol_Button] = ImVec4(0.84f, 0.87f, 0.92f, 1.0f);
    c[ImGuiCol_ButtonHovered] = ImVec4(0.70f, 0.79f, 0.92f, 1.0f);
    c[ImGuiCol_ButtonActive] = ImVec4(0.55f, 0.68f, 0.88f, 1.0f);
    c[ImGuiCol_FrameBg] = ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
    c[ImGuiCol_Border] = ImVec4(0.0f, 0.0f, 0.0f, 0.16f);
    c[ImGuiCol_FrameBgHovered] = ImVec4(0.93f, 0.95f, 0.99f, 1.0f);
    style.ScaleAllSizes(scale);

    std::error_code ec;
    if (std::filesystem::exists(kFontPath, ec)) {
        ImFontConfig config;
        config.OversampleH = 2;
        if (io.Fonts->AddFontFromFileTTF(kFontPath, 15.0f * scale, &config)) return "DejaVu Sans";
    }
    ImFontConfig config;
    config.SizePixels = 13.0f * scale;
    io.Fonts->AddFontDefault(&config);
    return "ImGui default";
}

ImVec4 ui_clear_color() {
    return ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
}

StudioApp::StudioApp(Studio& studio) : studio_(studio) {
    // A software rasterizer (llvmpipe on OSMesa, Xvfb or a remote desktop) pays for every MSAA
    // sample in fragment work, about twice the 3D view's cost at 4 samples: draw single-sampled
    // there and keep 4 samples on a GPU.
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string name = renderer ? renderer : "";
    if (name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos)
        studio.view.samples = 1;
}

void StudioApp::build_frame(double wall_dt_s) {
    Studio& s = studio_;
    s.ui.frame_dt_s = wall_dt_s;
    ++s.ui.frame;
    const auto update_start = std::chrono::steady_clock::now();
    update_studio(s);  // takes the workers' snapshots: must never wait for them
    const double update_ms =
        1000.0 *
        std::chrono::duration<double>(std::chrono::steady_clock::now() - update_start).count();
    s.ui.max_update_ms = std::max(s.ui.max_update_ms, update_ms);
    update_pending_action(s);
    take_file_dialog_keys(s);  // an open dialog takes the keys first
    dispatch_key_bindings(s);
    layout_and_panels();
    draw_confirm_dialogs(s);
    if (s.ui.screenshot_requested) {
        s.ui.screenshot_requested = false;
        // Numbered: a second F12 keeps the first screenshot.
        export_screenshot(s, renderer_, next_screenshot_path(s), s.exports.screenshot_width,
                          s.exports.screenshot_height);
    }
    continue_frame_export(s, renderer_);
}

void StudioApp::layout_and_panels() {
    Studio& s = studio_;
    draw_menu_bar(s);
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float top = ImGui::GetFrameHeight();
    const float status_h = ImGui::GetFrameHeight() + 2.0f;
    const float width = std::max(64.0f, display.x);
    const float height = std::max(100.0f, display.y - top - status_h);
    // The settings hold what the user chose; a small window only squeezes this frame's tiles.
    const TileLayout t = fit_layout(s.settings.layout, width, height);
    s.ui.tiles = t;
    const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoResize;

    // Left column: the design problem (in a narrow window a strip that opens it over the view,
    // drawn after the view so it lies on top).
    if (!t.left_collapsed) {
        s.ui.design_open = false;
        begin_tile("Design", {0, top}, {t.left, height}, fixed);
        draw_design_tabs(s, renderer_);
        ImGui::End();
    } else {
        ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(2.0f, 4.0f));
        begin_tile("Design strip", {0, top}, {t.left, height},
                   fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoTitleBar);
        ImGui::PopStyleVar();
        const bool clicked = ImGui::Button(s.ui.design_open ? "<###design" : ">###design",
                                           ImVec2(-1.0f, ImGui::GetFrameHeight() * 2.0f));
        record_widget(s, "design strip");
        if (clicked) {
            s.ui.design_open = !s.ui.design_open;
            design_just_opened_ = s.ui.design_open;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(s.ui.design_open
                                  ? "fold the Experiment, Constraints, Files and Export "
                                    "panels"
                                  : "Experiment, Constraints, Files, Export (the window "
                                    "is narrow: they open over the 3D view)");
        ImGui::End();
    }

    // Centre: the 3D view over the replay timeline.
    const float centre_x = t.left, centre_w = std::max(16.0f, width - t.left - t.right);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(4.0f, 4.0f));
    begin_tile("3D view", {centre_x, top}, {centre_w, t.view},
               fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
    ImGui::PopStyleVar();
    draw_viewport_panel(s, renderer_);
    ImGui::End();
    begin_tile("Replay", {centre_x, top + t.view}, {centre_w, t.bottom},
               fixed | ImGuiWindowFlags_NoScrollbar);
    draw_replay_panel(s);
    ImGui::End();

    // Right column: evolution.
    const float right_x = width - t.right;
    begin_tile("Run", {right_x, top}, {t.right, t.run}, fixed);
    draw_run_panel(s);
    ImGui::End();
    begin_tile("Fitness", {right_x, top + t.run}, {t.right, t.plot}, fixed);
    draw_fitness_panel(s);
    ImGui::End();
    begin_tile("Analysis", {right_x, top + t.run + t.plot}, {t.right, t.population}, fixed);
    record_widget_window(s, "analysis panel");  // its screenshot: the FEM tab's golden
    draw_analysis_panel(s);
    ImGui::End();

    if (t.left_collapsed && s.ui.design_open) {
        const float w = std::min(std::max(kMinSide, s.settings.layout.left_px),
                                 std::max(kMinSide, width * 0.75f - t.left));
        ImGui::SetNextWindowPos({t.left, top}, ImGuiCond_Always);
        ImGui::SetNextWindowSize({w, height}, ImGuiCond_Always);
        // Brought to the front once, as it opens (focused every frame it would take the mouse
        // from every other window's widgets).
        if (design_just_opened_) ImGui::SetNextWindowFocus();
        design_just_opened_ = false;
        ImGui::Begin("Design##open", nullptr,
                     ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoResize |
                         ImGuiWindowFlags_NoTitleBar);
        record_widget_window(s, "design panel");
        draw_design_tabs(s, renderer_);
        ImGui::End();
    }

    // The inner edges: drawn over the tiles, dragged to resize (bounded, remembered).
    constexpr float grip = 6.0f;
    if (!t.left_collapsed)
        splitter(s, "splitter left", {t.left - grip * 0.5f, top}, {grip, height}, Splitter::Left,
                 width, height);
    splitter(s, "splitter right", {right_x - grip * 0.5f, top}, {grip, height}, Splitter::Right,
             width, height);
    splitter(s, "splitter replay", {centre_x, top + t.view - grip * 0.5f}, {centre_w, grip},
             Splitter::Replay, width, height);
    splitter(s, "splitter run", {right_x, top + t.run - grip * 0.5f}, {t.right, grip},
             Splitter::RunPlot, width, height);
    splitter(s, "splitter plot", {right_x, top + t.run + t.plot - grip * 0.5f}, {t.right, grip},
             Splitter::PlotPopulation, width, height);

    // Status bar.
    ImGui::SetNextWindowPos({0, display.y - status_h}, ImGuiCond_Always);
    ImGui::SetNextWindowSize({display.x, status_h}, ImGuiCond_Always);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.0f, 2.0f));
    ImGui::Begin("##status", nullptr, ImGuiWindowFlags_NoDecoration | kTileFlags);
    ImGui::PopStyleVar();
    draw_status_bar(s);
    ImGui::End();

    draw_help_window(s);
    draw_welcome_window(s, renderer_, thumbnails_);
    draw_file_dialog(s);
}

void store_view_settings(Studio& s) {
    s.settings.camera.yaw_rad = s.view.camera.yaw_rad;
    s.settings.camera.pitch_rad = s.view.camera.pitch_rad;
    s.settings.camera.orthographic = s.view.camera.orthographic;
    s.settings.camera.zoom = s.view.zoom;
}

void restore_view_settings(Studio& s) {
    s.view.camera.yaw_rad = s.settings.camera.yaw_rad;
    s.view.camera.pitch_rad = s.settings.camera.pitch_rad;
    s.view.camera.orthographic = s.settings.camera.orthographic;
    s.view.camera.fov_y_rad = 0.55f;
    s.view.zoom = s.settings.camera.zoom;
    s.view.camera_needs_framing = true;
}

}  // namespace bhm::app::gui
