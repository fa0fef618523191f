// The Files tab: the shipped presets (a gallery, opened with one click), the recent files
// (absolute paths) and a file browser over std::filesystem: folders to walk into, experiment
// files to open, run directories to view. Every open goes through the unsaved-edits question.
#include <filesystem>
#include <string>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;

namespace {

// The listing is re-read twice a second at most: the panel is drawn every frame.
const FileListing& listing_of(Studio& s, const std::string& dir) {
    auto& cache = s.library.file_listings[dir];
    const auto now = std::chrono::steady_clock::now();
    if (!cache.valid || now - cache.read_at > std::chrono::milliseconds(500)) {
        cache = read_file_listing(dir);
        cache.read_at = now;
        cache.valid = true;
    }
    return cache;
}

void presets(Studio& s) {
    section_title("Presets");
    const auto& list = listing_of(s, s.library.presets_dir);
    if (list.experiments.empty()) {
        ImGui::TextDisabled("no presets in %s", s.library.presets_dir.c_str());
        return;
    }
    for (const auto& path : list.experiments) {
        const std::string stem = fs::path(path).stem().string();
        if (ImGui::Selectable(stem.c_str())) request_open_experiment(s, path);
        record_widget(s, "preset " + stem);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s\n(shipped: Save asks for a new name)", path.c_str());
    }
}

void recent(Studio& s) {
    section_title("Recent");
    if (s.settings.recent_files.empty()) ImGui::TextDisabled("no recent files");
    for (const auto& path : s.settings.recent_files) {
        const std::string name = fs::path(path).filename().string();
        if (ImGui::Selectable((name + "##" + path).c_str())) {
            request_open_experiment(s, std::string(path));
            break;  // the list changes
        }
        record_widget(s, "recent " + name);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
    }
}

void browser(Studio& s) {
    section_title("Browse");
    if (s.library.browser_dir.empty()) s.library.browser_dir = absolute_path(".");
    ImGui::TextWrapped("%s", s.library.browser_dir.c_str());
    const fs::path dir(s.library.browser_dir);
    if (dir.has_parent_path() && dir.parent_path() != dir) {
        if (ImGui::Selectable(".. (up)")) {
            s.library.browser_dir = dir.parent_path().string();
            return;
        }
        record_widget(s, "folder ..");
    }
    const auto& list = listing_of(s, s.library.browser_dir);
    if (!list.error.empty())
        ImGui::TextColored(ImVec4(0.8f, 0.15f, 0.1f, 1.0f), "%s", list.error.c_str());
    for (const auto& [path, is_run] : list.folders) {
        const std::string name = fs::path(path).filename().string();
        const std::string label = (is_run ? "[run] " : "[dir] ") + name + "##" + path;
        if (ImGui::Selectable(label.c_str())) {
            if (is_run) {
                s.run.open_field = path;
                open_run_directory(s, path);
            } else {
                s.library.browser_dir = path;
            }
            return;  // the listing changes
        }
        record_widget(s, "folder " + name);
        if (is_run && ImGui::IsItemHovered())
            ImGui::SetTooltip("a run directory: click to view it (Run > Resume run continues it)");
    }
    for (const auto& path : list.experiments) {
        const std::string name = fs::path(path).filename().string();
        if (ImGui::Selectable((name + "##" + path).c_str())) {
            s.path_field = path;
            request_open_experiment(s, path);
        }
        record_widget(s, "file " + name);
    }
}

}  // namespace

void draw_files_panel(Studio& s) {
    ImGui::BeginChild("files", ImVec2(0, 0));
    // One ID scope per section: the same file may be a preset, a recent file and in the browser.
    ImGui::PushID("presets");
    presets(s);
    ImGui::PopID();
    ImGui::PushID("recent");
    recent(s);
    ImGui::PopID();
    ImGui::PushID("browser");
    browser(s);
    ImGui::PopID();
    ImGui::EndChild();
}

}  // namespace bhm::app::gui
