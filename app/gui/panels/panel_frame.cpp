// The menu bar, the help window (every shortcut, from the one key-binding table) and the status
// bar.
#include <algorithm>

#include <imgui.h>

#include "app/gui/actions/controller_actions.hpp"
#include "app/gui/actions/key_bindings.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/file_dialog_widget.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

void draw_menu_bar(Studio& s) {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("New experiment", "Ctrl+N")) run_action(s, Action::NewExperiment);
        if (ImGui::MenuItem("Open...")) show_file_dialog(s, FileDialogPurpose::OpenExperiment);
        if (ImGui::MenuItem("Save", "Ctrl+S")) run_action(s, Action::SaveExperiment);
        if (ImGui::MenuItem("Save As..."))
            show_file_dialog(s, FileDialogPurpose::SaveExperimentAs);
        if (ImGui::MenuItem("Open run..."))
            show_file_dialog(s, FileDialogPurpose::OpenRun);
        if (ImGui::BeginMenu("Open recent", !s.settings.recent_files.empty())) {
            for (const auto& path : s.settings.recent_files)
                if (ImGui::MenuItem(path.c_str())) {
                    request_open_experiment(s, std::string(path));
                    break;
                }
            ImGui::EndMenu();
        }
        ImGui::Separator();
        // The shown champion's controller to the Export panel's path (issue 44).
        if (ImGui::MenuItem("Export controller.json", nullptr, false, s.bodies.shown != nullptr))
            export_shown_controller(s, s.exports.controller_path);
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) request_quit(s);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        const std::string undo_text = "Undo " + s.document.undo_label();
        const std::string redo_text = "Redo " + s.document.redo_label();
        if (ImGui::MenuItem(undo_text.c_str(), "Ctrl+Z", false, s.document.can_undo())) undo(s);
        if (ImGui::MenuItem(redo_text.c_str(), "Ctrl+Y", false, s.document.can_redo())) redo(s);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Run")) {
        if (ImGui::MenuItem("Start / resume", "F5")) run_action(s, Action::StartOrResumeRun);
        if (ImGui::MenuItem("Pause", "F6")) run_action(s, Action::PauseRun);
        if (ImGui::MenuItem("Stop", "Shift+F5")) run_action(s, Action::StopRun);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::MenuItem("Iso", "1")) run_action(s, Action::ViewIso);
        if (ImGui::MenuItem("Front", "2")) run_action(s, Action::ViewFront);
        if (ImGui::MenuItem("Top", "3")) run_action(s, Action::ViewTop);
        if (ImGui::MenuItem("Side", "4")) run_action(s, Action::ViewSide);
        ImGui::Separator();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0f);
        float scale = s.settings.ui_scale;
        if (ImGui::SliderFloat("UI scale (HiDPI)", &scale, 0.5f, 3.0f, "%.2f"))
            s.settings.ui_scale = scale;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("takes effect at the next start");
        ImGui::MenuItem("Frame-time overlay", nullptr, &s.ui.show_demo_metrics);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("Shortcuts and mouse", "F1")) s.ui.show_help = true;
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void draw_help_window(Studio& s) {
    if (!s.ui.show_help) return;
    // Tall enough for every shortcut (wrapped) at the usual window sizes; smaller windows scroll.
    centre_next_window(60.0f, 44.0f, ImGuiCond_Appearing);
    if (!ImGui::Begin("Help: shortcuts and mouse", &s.ui.show_help, ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
    {  // recorded so tests can check that every line is inside it
        const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        s.ui.widgets["help window"] =
            WidgetRect{{pos.x, pos.y}, {pos.x + size.x, pos.y + size.y}, s.ui.frame};
    }
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
    if (ImGui::BeginTable("help layout", 2, ImGuiTableFlags_SizingStretchSame)) {
        ImGui::TableNextColumn();
        section_title("Keyboard");
        if (ImGui::BeginTable("keys", 2, flags)) {
            // The key column as wide as its widest chord ("Ctrl+Shift+Z"); descriptions wrap.
            float keys_width = 0.0f;
            for (const auto& b : key_bindings())
                keys_width = std::max(keys_width, ImGui::CalcTextSize(b.keys).x);
            ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, keys_width);
            ImGui::TableSetupColumn("what", ImGuiTableColumnFlags_WidthStretch);
            for (const auto& b : key_bindings()) {
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(b.keys);
                record_widget(s, std::string("help keys: ") + b.keys);
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", b.description);
                record_widget(s, std::string("help: ") + b.keys);
            }
            ImGui::EndTable();
        }
        ImGui::TableNextColumn();
        section_title("Mouse in the 3D view");
        if (ImGui::BeginTable("mouse", 2, flags)) {
            for (const auto& [gesture, what] : mouse_gestures()) {
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", gesture);
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", what);
            }
            ImGui::EndTable();
        }
        section_title("Units");
        ImGui::TextWrapped(
            "Inputs are SI (m, s, Pa, kg/m^3, Hz, degC). Fitness is in voxel lengths "
            "(centre-of-mass measures) or degrees (bend angle), measured from the end of "
            "settling.");
        section_title("Colours");
        ImGui::TextWrapped(
            "Green faces are fixed, purple faces free. Hatched voxels are held; dark "
            "translucent cells are forbidden; grey translucent cells are the enclosure frame. "
            "The yellow star marks the body's first voxel, cell (0, 0, 0), the lattice's "
            "origin. The orange line is the centre-of-mass trail; an orange box outlines the "
            "voxel clicked in Simulation mode.");
        ImGui::TextWrapped(
            "Simulation mode: fixed faces are hatched green just outside the workspace. The "
            "colour menu paints the body by material, displacement from t = 0 (voxel lengths), "
            "volumetric strain or the muscles' actuation signal; the bar at the right gives "
            "the range. An orange \"simulating ...\" line means the body shown is not yet "
            "the one asked for.");
        ImGui::EndTable();
    }
    ImGui::End();
}

void draw_status_bar(Studio& s) {
    const auto& doc = s.document;
    ImGui::TextUnformatted(document_label(doc).c_str());
    if (doc.dirty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(0.75f, 0.45f, 0.0f, 1.0f), "(modified)");
    }
    ImGui::SameLine();
    ImGui::TextDisabled("|");
    ImGui::SameLine();
    if (s.ui.status_is_error)
        ImGui::TextColored(ImVec4(0.80f, 0.15f, 0.10f, 1.0f), "%s", s.ui.status.c_str());
    else
        ImGui::TextUnformatted(s.ui.status.c_str());
    if (s.ui.status_is_error && s.ui.edit_problems.size() > 1 && ImGui::IsItemHovered()) {
        // The line may be cut at the window's edge: the tooltip lists every problem in full.
        ImGui::BeginTooltip();
        for (const auto& problem : s.ui.edit_problems)
            ImGui::Text("%s: %s", problem.field.c_str(), problem.message.c_str());
        ImGui::EndTooltip();
    }
    if (s.ui.show_demo_metrics) {
        char fps[48];
        std::snprintf(fps, sizeof fps, "%.0f fps (%.1f ms)", s.ui.fps,
                      s.ui.fps > 0 ? 1000.0 / s.ui.fps : 0.0);
        ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(fps).x -
                        ImGui::GetStyle().WindowPadding.x);
        ImGui::TextDisabled("%s", fps);
    }
}

}  // namespace bhm::app::gui
