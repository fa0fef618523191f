#include "app/gui/panels/file_dialog_widget.hpp"

#include <cstdio>
#include <filesystem>

#define GLFW_INCLUDE_NONE  // GL comes from glad only
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/gui/actions/calibration_actions.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;

namespace {

void apply_choice(Studio& s, FileDialogPurpose purpose, const std::string& path) {
    switch (purpose) {
        case FileDialogPurpose::OpenExperiment:
            s.path_field = path;
            request_open_experiment(s, path);
            break;
        case FileDialogPurpose::SaveExperimentAs:
            s.path_field = path;
            save_experiment_as(s, path);
            break;
        case FileDialogPurpose::OpenRun:
            s.run.open_field = path;
            open_run_directory(s, path);
            break;
        case FileDialogPurpose::CompareRun:
            s.run.compare_field = path;
            add_compared_run(s, path);
            break;
        case FileDialogPurpose::ShowBody:
            s.calibration.body_field = path;
            show_body_file(s, path);
            break;
        case FileDialogPurpose::LoadTrack:
            s.calibration.track_field = path;
            load_track(s, path);
            break;
    }
}

std::string parent_of(const std::string& path) {
    return path.empty() ? std::string() : fs::path(path).parent_path().string();
}

const char* ok_label(FileDialogPurpose purpose) {
    switch (purpose) {
        case FileDialogPurpose::OpenExperiment:
            return "Open";
        case FileDialogPurpose::SaveExperimentAs:
            return "Save";
        case FileDialogPurpose::OpenRun:
            return "View";
        case FileDialogPurpose::CompareRun:
            return "Compare";
        case FileDialogPurpose::ShowBody:
            return "Show";
        case FileDialogPurpose::LoadTrack:
            return "Load";
    }
    return "OK";
}

}  // namespace

void show_file_dialog(Studio& s, FileDialogPurpose purpose) {
    std::string dir = s.library.browser_dir;
    std::string name;
    const bool experiment = purpose == FileDialogPurpose::SaveExperimentAs ||
                            purpose == FileDialogPurpose::OpenExperiment;
    // A path typed in the panel's field goes into the dialog's name field: Enter takes it.
    const std::string& typed = experiment                                ? s.path_field
                               : purpose == FileDialogPurpose::ShowBody  ? s.calibration.body_field
                               : purpose == FileDialogPurpose::LoadTrack ? s.calibration.track_field
                                                                         : s.run.open_field;
    if (experiment) {
        if (!s.document.path().empty()) dir = parent_of(s.document.path());
        if (purpose == FileDialogPurpose::SaveExperimentAs)
            name = s.document.path().empty() ? s.document.experiment().name + ".json"
                                             : fs::path(s.document.path()).filename().string();
    } else if (purpose_wants_run(purpose) && s.run.snapshot && !s.run.snapshot->run_dir.empty()) {
        dir = parent_of(s.run.snapshot->run_dir);
    }
    if (!typed.empty() && typed != s.document.path()) {
        name = typed;
        std::error_code ec;
        const std::string parent = parent_of(absolute_path(typed));
        if (fs::is_directory(parent, ec)) dir = parent;
    }
    open_file_dialog(s.ui.file_dialog, purpose, dir, name);
}

void take_file_dialog_keys(Studio& s) {
    if (!s.ui.file_dialog.open) return;
    std::vector<KeyChord> presses;
    presses.swap(s.ui.key_presses);
    for (const KeyChord& k : presses) {
        // A held Up / Down moves on with the system's key repeat; Enter, Backspace and Escape
        // act once per press (a held Backspace must not climb to the root).
        if (k.repeat && k.key != GLFW_KEY_UP && k.key != GLFW_KEY_DOWN) continue;
        std::optional<FileDialogKey> key;
        switch (k.key) {
            case GLFW_KEY_UP:
                key = FileDialogKey::Up;
                break;
            case GLFW_KEY_DOWN:
                key = FileDialogKey::Down;
                break;
            case GLFW_KEY_ENTER:
            case GLFW_KEY_KP_ENTER:
                key = FileDialogKey::Enter;
                break;
            case GLFW_KEY_BACKSPACE:
                key = FileDialogKey::Backspace;
                break;
            case GLFW_KEY_ESCAPE:
                key = FileDialogKey::Escape;
                break;
            default:
                break;
        }
        if (!key) continue;
        const FileDialogPurpose purpose = s.ui.file_dialog.purpose;
        if (const auto chosen = file_dialog_key(s.ui.file_dialog, *key)) {
            apply_choice(s, purpose, *chosen);
            return;
        }
        if (!s.ui.file_dialog.open) return;
    }
}

void draw_file_dialog(Studio& s) {
    FileDialog& d = s.ui.file_dialog;
    if (!d.open) return;
    centre_next_window(40.0f, 30.0f, ImGuiCond_Appearing);
    ImGui::SetNextWindowFocus();
    bool open = true;
    const std::string title = std::string(file_dialog_title(d.purpose)) + "###file dialog";
    if (!ImGui::Begin(title.c_str(), &open, ImGuiWindowFlags_NoCollapse)) {
        ImGui::End();
        return;
    }
    {
        const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        s.ui.widgets["file dialog"] =
            WidgetRect{{pos.x, pos.y}, {pos.x + size.x, pos.y + size.y}, s.ui.frame};
    }
    ImGui::TextWrapped("%s", d.dir.c_str());
    ImGui::TextDisabled("%s; Up/Down, Enter, Backspace: parent, Esc",
                        purpose_wants_run(d.purpose)                 ? "run directories [run]"
                        : d.purpose == FileDialogPurpose::LoadTrack  ? "folders and *.csv tracks"
                        : d.purpose == FileDialogPurpose::ShowBody   ? "folders and *.json bodies"
                                                                     : "folders and *.json experiments");
    const float footer =
        ImGui::GetFrameHeightWithSpacing() * 2.0f + ImGui::GetTextLineHeightWithSpacing();
    std::optional<std::string> chosen;
    const FileDialogPurpose purpose = d.purpose;
    ImGui::BeginChild("entries", ImVec2(0, -footer), true);
    for (std::size_t i = 0; i < d.entries.size() && d.open; ++i) {
        const auto& e = d.entries[i];
        const bool run = e.kind == FileDialogEntry::Kind::Run;
        const std::string label = (run ? "[run] " : "") + e.name + "##" + std::to_string(i);
        const bool is_selected = static_cast<int>(i) == d.selected;
        if (ImGui::Selectable(label.c_str(), is_selected)) {
            d.selected = static_cast<int>(i);
            chosen = file_dialog_activate(d, i);
        }
        record_widget(s, "dialog entry " + e.name);
        if (is_selected && d.scroll_to_selected) {
            ImGui::SetScrollHereY();
            d.scroll_to_selected = false;
        }
        if (chosen || !d.open) break;
        if (i >= d.entries.size()) break;
    }
    ImGui::EndChild();
    if (!chosen && d.open) {
        char buffer[1024];
        std::snprintf(buffer, sizeof buffer, "%s", d.name.c_str());
        ImGui::SetNextItemWidth(-1.0f);
        if (ImGui::InputTextWithHint("##dialog name",
                                     purpose == FileDialogPurpose::SaveExperimentAs
                                         ? "file name (.json)"
                                         : "or type a path",
                                     buffer, sizeof buffer))
            d.name = buffer;
        record_widget(s, "dialog name");
        if (!d.error.empty())
            ImGui::TextColored(ImVec4(0.8f, 0.15f, 0.1f, 1.0f), "%s", d.error.c_str());
        if (ImGui::Button(ok_label(purpose))) chosen = file_dialog_key(d, FileDialogKey::Enter);
        record_widget(s, "dialog ok");
        ImGui::SameLine();
        if (ImGui::Button("Cancel##dialog")) d.open = false;
        record_widget(s, "dialog cancel");
    }
    if (!open) d.open = false;
    ImGui::End();
    if (chosen) apply_choice(s, purpose, *chosen);
}

}  // namespace bhm::app::gui
