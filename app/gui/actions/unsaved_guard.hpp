#pragma once
// Nothing is lost without asking: New, Open (the path field, Recent, the file browser), Ctrl+Q and
// closing the window first ask what to do with unsaved edits (Save, Discard, Cancel: Cancel keeps
// the document and its undo history as they were), and quitting while a run is going asks whether
// to wait for the generation in progress or abandon it (the last checkpoint is kept either way).
// The action waits in studio.ui.pending until answered; panels/panel_confirm_dialogs.cpp shows
// the questions.
#include <string>

#include "app/gui/studio.hpp"

namespace bhm::app::gui {

void request_new_experiment(Studio& studio);
void request_open_experiment(Studio& studio, const std::string& path);
void request_quit(Studio& studio);
//! The window's close button: asks like request_quit; true when the window may close now.
bool window_close_requested(Studio& studio);

enum class UnsavedAnswer { Save, Discard, Cancel };
void answer_unsaved(Studio& studio, UnsavedAnswer answer);

enum class QuitRunAnswer { FinishGeneration, QuitNow, Cancel };
void answer_quit_run(Studio& studio, QuitRunAnswer answer);

//! The unsaved-edits question is showing.
bool asking_unsaved(const Studio& studio);
//! The quit-while-running question is showing.
bool asking_quit_run(const Studio& studio);
//! What that question says about the checkpoint: the completed generations kept, or, in
//! generation 0, that there is no checkpoint and the run cannot be resumed.
std::string quit_run_question(const Studio& studio);

//! Per frame: a quit waiting for the generation in progress goes on once the run has paused.
void update_pending_action(Studio& studio);

}  // namespace bhm::app::gui
