#pragma once
// Draws the studio's file dialog (file_dialog.hpp) as a window over the tiles and applies what it
// chooses: Open (through the unsaved-edits question), Save As, View a run, Compare with a run.
#include "app/gui/studio.hpp"

namespace bhm::app::gui {

//! Opens the dialog for a purpose in the folder that suits it (the document's, the run's, the
//! browser's).
void show_file_dialog(Studio& studio, FileDialogPurpose purpose);
//! While the dialog is open it takes the frame's key presses (Up, Down, Enter, Backspace,
//! Escape move and choose; the others are dropped, so no shortcut acts behind it). Call before
//! dispatch_key_bindings.
void take_file_dialog_keys(Studio& studio);
void draw_file_dialog(Studio& studio);

}  // namespace bhm::app::gui
