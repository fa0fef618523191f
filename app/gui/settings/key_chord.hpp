#pragma once
// One key press as the studio reads it (a key and its modifiers), from a script's text ("ctrl+z")
// or from a window's key event. Plain data below the actions, so the studio's state can queue
// presses (studio.ui.key_presses) without knowing the table of shortcuts
// (actions/key_bindings.hpp).
#include <optional>
#include <string>

namespace bhm::app::gui {

//! Parses "ctrl+z", "shift+f5", "space", "f1", "left" into a key and modifiers.
struct KeyChord {
    int key = 0;
    bool ctrl = false, shift = false;
    //! The system's key repeat while the key is held (GLFW_REPEAT), not a new press: shortcuts
    //! act once per press, the file dialog's Up / Down move on with it.
    bool repeat = false;
};
std::optional<KeyChord> parse_key_chord(const std::string& text);

//! What one key event of the window (GLFW key, action and modifiers) adds to studio.ui.key_presses:
//! a press, or a repeat while the key is held; nothing for a release. The window's key callback
//! and the headless script's held keys both go through it.
std::optional<KeyChord> key_event_chord(int key, int action, int mods);

}  // namespace bhm::app::gui
