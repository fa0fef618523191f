#include "app/gui/actions/unsaved_guard.hpp"

#include "app/gui/actions/studio_actions.hpp"

namespace bhm::app::gui {

namespace {

bool waiting_for_generation(const Studio& s) {
    return s.ui.pending.kind == PendingAction::Kind::Quit && s.ui.pending.quit_after_generation;
}

// Does the pending action when nothing is left to ask.
void proceed(Studio& s) {
    PendingAction& p = s.ui.pending;
    if (p.kind == PendingAction::Kind::None) return;
    if (s.document.dirty() && !p.unsaved_answered) return;  // the dialog asks
    switch (p.kind) {
        case PendingAction::Kind::NewExperiment:
            p = {};
            new_experiment(s);
            return;
        case PendingAction::Kind::OpenExperiment: {
            const std::string path = p.path;
            p = {};
            open_experiment(s, path);
            return;
        }
        case PendingAction::Kind::Quit:
            if (run_is_live(s.run.evolution.phase()) && !p.run_answered) return;  // the dialog asks
            if (p.quit_after_generation && run_is_live(s.run.evolution.phase()) &&
                s.run.evolution.phase() != RunPhase::Paused)
                return;  // update_pending_action quits once the generation is done
            p = {};
            s.ui.quit_requested = true;
            return;
        case PendingAction::Kind::None:
            return;
    }
}

}  // namespace

void request_new_experiment(Studio& s) {
    s.ui.pending = {};
    s.ui.pending.kind = PendingAction::Kind::NewExperiment;
    proceed(s);
}

void request_open_experiment(Studio& s, const std::string& path) {
    s.ui.pending = {};
    s.ui.pending.kind = PendingAction::Kind::OpenExperiment;
    s.ui.pending.path = path;
    proceed(s);
}

void request_quit(Studio& s) {
    if (s.ui.pending.kind == PendingAction::Kind::Quit) return;  // already asking
    s.ui.pending = {};
    s.ui.pending.kind = PendingAction::Kind::Quit;
    proceed(s);
}

bool window_close_requested(Studio& s) {
    request_quit(s);
    return s.ui.quit_requested;
}

bool asking_unsaved(const Studio& s) {
    return s.ui.pending.kind != PendingAction::Kind::None && s.document.dirty() &&
           !s.ui.pending.unsaved_answered;
}

bool asking_quit_run(const Studio& s) {
    return s.ui.pending.kind == PendingAction::Kind::Quit && !asking_unsaved(s) &&
           !s.ui.pending.run_answered && run_is_live(s.run.evolution.phase());
}

void answer_unsaved(Studio& s, UnsavedAnswer answer) {
    switch (answer) {
        case UnsavedAnswer::Save:
            if (!save_experiment(s)) {  // the question stays and says why
                s.ui.pending.error = s.ui.status;
                return;
            }
            s.ui.pending.unsaved_answered = true;
            break;
        case UnsavedAnswer::Discard:
            s.ui.pending.unsaved_answered = true;
            break;
        case UnsavedAnswer::Cancel:
            s.ui.pending = {};
            set_status(s, "cancelled: the experiment and its undo history are kept");
            return;
    }
    proceed(s);
}

std::string quit_run_question(const Studio& s) {
    const int done = s.run.snapshot && s.run.snapshot->loaded ? s.run.snapshot->generation : 0;
    if (done == 0)  // no checkpoint is written before generation 0 completes
        return "Quitting now abandons generation 0, the first: no generation is complete, so "
               "there is no checkpoint and the run cannot be resumed.";
    return "Quitting now abandons the generation in progress; the checkpoint of the " +
           std::to_string(done) + " completed generation" + (done == 1 ? "" : "s") +
           " is kept and the run can be resumed.";
}

void answer_quit_run(Studio& s, QuitRunAnswer answer) {
    switch (answer) {
        case QuitRunAnswer::FinishGeneration:
            s.ui.pending.run_answered = true;
            s.ui.pending.quit_after_generation = true;
            s.run.evolution.pause(/*between_generations=*/true);  // it finishes and is saved
            set_status(s, "quitting once the generation in progress is done and saved");
            break;
        case QuitRunAnswer::QuitNow:
            s.ui.pending.run_answered = true;
            break;
        case QuitRunAnswer::Cancel:
            s.ui.pending = {};
            set_status(s, "quit cancelled: the run goes on");
            return;
    }
    proceed(s);
}

void update_pending_action(Studio& s) {
    if (waiting_for_generation(s)) proceed(s);
}

}  // namespace bhm::app::gui
