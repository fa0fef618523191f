#include "app/gui/actions/unsaved_guard.hpp"

#include "app/gui/actions/studio_actions.hpp"

namespace bhm::app::gui {

namespace {

bool waiting_for_generation(const Studio& s) {
    return s.pending.kind == PendingAction::Kind::Quit && s.pending.quit_after_generation;
}

// Does the pending action when nothing is left to ask.
void proceed(Studio& s) {
    PendingAction& p = s.pending;
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
            if (run_is_live(s.evolution.phase()) && !p.run_answered) return;  // the dialog asks
            if (p.quit_after_generation && run_is_live(s.evolution.phase()) &&
                s.evolution.phase() != RunPhase::Paused)
                return;  // update_pending_action quits once the generation is done
            p = {};
            s.quit_requested = true;
            return;
        case PendingAction::Kind::None:
            return;
    }
}

}  // namespace

void request_new_experiment(Studio& s) {
    s.pending = {};
    s.pending.kind = PendingAction::Kind::NewExperiment;
    proceed(s);
}

void request_open_experiment(Studio& s, const std::string& path) {
    s.pending = {};
    s.pending.kind = PendingAction::Kind::OpenExperiment;
    s.pending.path = path;
    proceed(s);
}

void request_quit(Studio& s) {
    if (s.pending.kind == PendingAction::Kind::Quit) return;  // already asking
    s.pending = {};
    s.pending.kind = PendingAction::Kind::Quit;
    proceed(s);
}

bool window_close_requested(Studio& s) {
    request_quit(s);
    return s.quit_requested;
}

bool asking_unsaved(const Studio& s) {
    return s.pending.kind != PendingAction::Kind::None && s.document.dirty() &&
           !s.pending.unsaved_answered;
}

bool asking_quit_run(const Studio& s) {
    return s.pending.kind == PendingAction::Kind::Quit && !asking_unsaved(s) &&
           !s.pending.run_answered && run_is_live(s.evolution.phase());
}

void answer_unsaved(Studio& s, UnsavedAnswer answer) {
    switch (answer) {
        case UnsavedAnswer::Save:
            if (!save_experiment(s)) {  // the question stays and says why
                s.pending.error = s.status;
                return;
            }
            s.pending.unsaved_answered = true;
            break;
        case UnsavedAnswer::Discard:
            s.pending.unsaved_answered = true;
            break;
        case UnsavedAnswer::Cancel:
            s.pending = {};
            set_status(s, "cancelled: the experiment and its undo history are kept");
            return;
    }
    proceed(s);
}

std::string quit_run_question(const Studio& s) {
    const int done = s.run && s.run->loaded ? s.run->generation : 0;
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
            s.pending.run_answered = true;
            s.pending.quit_after_generation = true;
            s.evolution.pause(/*between_generations=*/true);  // it finishes and is saved
            set_status(s, "quitting once the generation in progress is done and saved");
            break;
        case QuitRunAnswer::QuitNow:
            s.pending.run_answered = true;
            break;
        case QuitRunAnswer::Cancel:
            s.pending = {};
            set_status(s, "quit cancelled: the run goes on");
            return;
    }
    proceed(s);
}

void update_pending_action(Studio& s) {
    if (waiting_for_generation(s)) proceed(s);
}

}  // namespace bhm::app::gui
