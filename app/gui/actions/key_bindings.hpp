#pragma once
// The one table of keyboard shortcuts: dispatched every frame, listed in the help panel, and
// used by scripts ("key": "ctrl+z") through the same path. Keys are GLFW key codes, which the
// GLFW backend writes into io.KeysDown and the headless runner mirrors.
#include <optional>
#include <string>
#include <vector>

#include "app/gui/settings/key_chord.hpp"

namespace bhm::app::gui {

struct Studio;

enum class Action {
    Undo,
    Redo,
    NewExperiment,
    SaveExperiment,
    StartOrResumeRun,
    PauseRun,
    StopRun,
    PlayPause,
    StepBack,
    StepForward,
    ReplayStart,
    ReplayEnd,
    ToggleViewMode,
    ViewIso,
    ViewFront,
    ViewTop,
    ViewSide,
    ToolFaces,
    ToolVoxels,
    Screenshot,
    ToggleHelp,
    Quit,
};

struct KeyBinding {
    int key = 0;  //!< GLFW key code
    bool ctrl = false;
    bool shift = false;
    Action action = Action::Undo;
    const char* keys;         //!< as shown in the help panel, e.g. "Ctrl+Z"
    const char* description;  //!< what it does
};

const std::vector<KeyBinding>& key_bindings();

//! Mouse gestures of the 3D view, for the help panel (pairs: gesture, what it does).
const std::vector<std::pair<const char*, const char*>>& mouse_gestures();

//! Runs the bound actions of the presses since the last frame (studio.ui.key_presses, filled by the
//! window's key callback or the headless input; emptied here). Call between NewFrame and Render.
//! Skipped while a text field has the keyboard, so typing never triggers shortcuts.
void dispatch_key_bindings(Studio& studio);

//! Runs one action (the menu and the toolbar call this too).
void run_action(Studio& studio, Action action);

}  // namespace bhm::app::gui
