// The modal questions of actions/unsaved_guard.hpp: unsaved edits before New, Open or Quit, and
// quitting while a run is going. The answers go back through answer_unsaved / answer_quit_run.
#include <algorithm>

#include <imgui.h>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

constexpr const char* kUnsavedTitle = "Unsaved changes";
constexpr const char* kQuitRunTitle = "Evolution is running";

}  // namespace

void draw_confirm_dialogs(Studio& s) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const ImVec2 centre(display.x * 0.5f, display.y * 0.5f);
    const float width = std::min(display.x - 20.0f, ImGui::GetFontSize() * 30.0f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove;

    if (asking_unsaved(s) && !ImGui::IsPopupOpen(kUnsavedTitle)) ImGui::OpenPopup(kUnsavedTitle);
    ImGui::SetNextWindowPos(centre, ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    if (ImGui::BeginPopupModal(kUnsavedTitle, nullptr, flags)) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
        const char* what = s.ui.pending.kind == PendingAction::Kind::Quit ? "Quit"
                           : s.ui.pending.kind == PendingAction::Kind::NewExperiment
                               ? "New experiment"
                               : "Open";
        ImGui::TextWrapped("%s has unsaved edits. %s would discard them and their undo history.",
                           document_label(s.document).c_str(), what);
        if (s.ui.pending.kind == PendingAction::Kind::OpenExperiment)
            ImGui::TextDisabled("open: %s", s.ui.pending.path.c_str());
        // Only this question's own failure: an older error in the status bar (say, another file
        // that did not open) is not about it.
        if (!s.ui.pending.error.empty()) {
            ImGui::TextColored(ImVec4(0.8f, 0.15f, 0.1f, 1.0f), "%s", s.ui.pending.error.c_str());
            record_widget(s, "dialog error");
        }
        ImGui::PopTextWrapPos();
        if (tracked_button(s, "Save changes")) answer_unsaved(s, UnsavedAnswer::Save);
        ImGui::SameLine();
        if (tracked_button(s, "Discard changes")) answer_unsaved(s, UnsavedAnswer::Discard);
        ImGui::SameLine();
        if (tracked_button(s, "Cancel##unsaved")) answer_unsaved(s, UnsavedAnswer::Cancel);
        if (!asking_unsaved(s)) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }

    if (asking_quit_run(s) && !ImGui::IsPopupOpen(kQuitRunTitle)) ImGui::OpenPopup(kQuitRunTitle);
    ImGui::SetNextWindowPos(centre, ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    if (ImGui::BeginPopupModal(kQuitRunTitle, nullptr, flags)) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
        ImGui::TextWrapped("%s", quit_run_question(s).c_str());
        ImGui::PopTextWrapPos();
        if (tracked_button(s, "Finish generation, then quit"))
            answer_quit_run(s, QuitRunAnswer::FinishGeneration);
        ImGui::SameLine();
        if (tracked_button(s, "Quit now")) answer_quit_run(s, QuitRunAnswer::QuitNow);
        ImGui::SameLine();
        if (tracked_button(s, "Cancel##quit")) answer_quit_run(s, QuitRunAnswer::Cancel);
        if (!asking_quit_run(s)) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
}

}  // namespace bhm::app::gui
