#include "app/gui/actions/key_bindings.hpp"

#define GLFW_INCLUDE_NONE  // GL comes from glad only
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cctype>

#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/actions/unsaved_guard.hpp"

namespace bhm::app::gui {

const std::vector<KeyBinding>& key_bindings() {
    static const std::vector<KeyBinding> table = {
        {GLFW_KEY_Z, true, false, Action::Undo, "Ctrl+Z", "undo the last edit"},
        {GLFW_KEY_Y, true, false, Action::Redo, "Ctrl+Y", "redo"},
        {GLFW_KEY_Z, true, true, Action::Redo, "Ctrl+Shift+Z", "redo"},
        {GLFW_KEY_N, true, false, Action::NewExperiment, "Ctrl+N", "new experiment"},
        {GLFW_KEY_S, true, false, Action::SaveExperiment, "Ctrl+S", "save the experiment"},
        {GLFW_KEY_F5, false, false, Action::StartOrResumeRun, "F5", "start or resume evolution"},
        {GLFW_KEY_F6, false, false, Action::PauseRun, "F6", "pause evolution"},
        {GLFW_KEY_F5, false, true, Action::StopRun, "Shift+F5", "stop evolution"},
        {GLFW_KEY_SPACE, false, false, Action::PlayPause, "Space", "play / pause the replay"},
        {GLFW_KEY_LEFT, false, false, Action::StepBack, "Left", "one replay frame back"},
        {GLFW_KEY_RIGHT, false, false, Action::StepForward, "Right", "one replay frame forward"},
        {GLFW_KEY_HOME, false, false, Action::ReplayStart, "Home", "replay to t = 0"},
        {GLFW_KEY_END, false, false, Action::ReplayEnd, "End", "replay to the end"},
        {GLFW_KEY_TAB, false, false, Action::ToggleViewMode, "Tab",
         "switch the 3D view: workspace / simulation"},
        {GLFW_KEY_1, false, false, Action::ViewIso, "1", "isometric view"},
        {GLFW_KEY_2, false, false, Action::ViewFront, "2", "front view (along -y)"},
        {GLFW_KEY_3, false, false, Action::ViewTop, "3", "top view"},
        {GLFW_KEY_4, false, false, Action::ViewSide, "4", "side view (along -x)"},
        {GLFW_KEY_F, false, false, Action::ToolFaces, "F", "painter: click faces (free / fixed)"},
        {GLFW_KEY_V, false, false, Action::ToolVoxels, "V", "painter: paint voxels with the brush"},
        {GLFW_KEY_F12, false, false, Action::Screenshot, "F12",
         "screenshot of the 3D view (Export panel size and path)"},
        {GLFW_KEY_F1, false, false, Action::ToggleHelp, "F1", "show / hide this help"},
        {GLFW_KEY_Q, true, false, Action::Quit, "Ctrl+Q", "quit (asks first about unsaved edits and a running evolution)"},
    };
    return table;
}

const std::vector<std::pair<const char*, const char*>>& mouse_gestures() {
    static const std::vector<std::pair<const char*, const char*>> table = {
        {"Left drag", "orbit the camera"},
        {"Right or middle drag", "pan"},
        {"Wheel", "zoom"},
        {"Left click (Faces tool)", "cycle the face under the cursor: free / fixed"},
        {"Left click (Voxels tool)", "paint the cell under the cursor with the brush"},
        {"Shift + left click (Voxels)", "clear the cell's override"},
        {"Left click (Simulation)",
         "read the voxel under the cursor at the replay time: cell, material, displacement, "
         "strain, actuation (a click beside the body clears it)"},
    };
    return table;
}

void dispatch_key_bindings(Studio& studio) {
    // Each press with the modifiers held at that moment, in order, even when the key (or Ctrl)
    // was released before this frame: a quick Ctrl+Z was lost when only the keys still down at
    // the frame's start counted.
    std::vector<KeyChord> presses;
    presses.swap(studio.ui.key_presses);
    if (ImGui::GetIO().WantTextInput) return;
    for (const KeyChord& press : presses) {
        if (press.repeat) continue;  // a held F5 or Ctrl+Z acts once
        for (const auto& binding : key_bindings())
            if (binding.key == press.key && binding.ctrl == press.ctrl &&
                binding.shift == press.shift)
                run_action(studio, binding.action);
    }
}

void run_action(Studio& studio, Action action) {
    switch (action) {
        case Action::Undo:
            undo(studio);
            break;
        case Action::Redo:
            redo(studio);
            break;
        case Action::NewExperiment:
            request_new_experiment(studio);
            break;
        case Action::SaveExperiment:
            save_experiment(studio);
            break;
        case Action::StartOrResumeRun:
            if (!resume_run(studio)) start_run(studio);
            break;
        case Action::PauseRun:
            pause_run(studio);
            break;
        case Action::StopRun:
            stop_run(studio);
            break;
        case Action::PlayPause:
            toggle_playback(studio);
            break;
        case Action::StepBack:
            step_replay(studio, -1);
            break;
        case Action::StepForward:
            step_replay(studio, 1);
            break;
        case Action::ReplayStart:
            studio.clock.seek(0.0);
            break;
        case Action::ReplayEnd:
            studio.clock.seek(studio.clock.duration_s);
            break;
        case Action::ToggleViewMode:
            set_view_mode(studio, studio.view.mode == ViewMode::Workspace ? ViewMode::Simulation
                                                                          : ViewMode::Workspace);
            break;
        case Action::ViewIso:
            set_named_view(studio, render::NamedView::Iso);
            break;
        case Action::ViewFront:
            set_named_view(studio, render::NamedView::Front);
            break;
        case Action::ViewTop:
            set_named_view(studio, render::NamedView::Top);
            break;
        case Action::ViewSide:
            set_named_view(studio, render::NamedView::Side);
            break;
        case Action::ToolFaces:
            studio.painter.tool = PainterTool::Faces;
            set_view_mode(studio, ViewMode::Workspace);
            break;
        case Action::ToolVoxels:
            studio.painter.tool = PainterTool::Voxels;
            set_view_mode(studio, ViewMode::Workspace);
            break;
        case Action::Screenshot:
            studio.ui.screenshot_requested = true;
            break;
        case Action::ToggleHelp:
            studio.ui.show_help = !studio.ui.show_help;
            break;
        case Action::Quit:
            request_quit(studio);
            break;
    }
}

}  // namespace bhm::app::gui
