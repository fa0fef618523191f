#include "app/gui/document/experiment_document.hpp"

#include <atomic>
#include <limits>

#include "app/gui/document/studio_defaults.hpp"

namespace bhm::app::gui {

ExperimentDocument::ExperimentDocument() {
    reset(default_experiment(), "");
}

std::vector<evo::Problem> ExperimentDocument::edit(const evo::Experiment& next,
                                                   const std::string& label) {
    auto problems = evo::validate_experiment(next, document_label(*this));
    if (!problems.empty()) return problems;
    if (next == experiment()) return {};
    history_.resize(position_ + 1);  // an edit after undo drops the redo branch
    history_.push_back({next, label});
    ++position_;
    if (history_.size() > kMaxHistory + 1) {
        history_.erase(history_.begin());
        --position_;
        // The saved state fell off the history: it can never be reached again.
        saved_position_ =
            saved_position_ == 0 ? std::numeric_limits<std::size_t>::max() : saved_position_ - 1;
    }
    ++revision_;
    return {};
}

std::string ExperimentDocument::undo_label() const {
    return can_undo() ? history_[position_].label : "";
}

std::string ExperimentDocument::redo_label() const {
    return can_redo() ? history_[position_ + 1].label : "";
}

bool ExperimentDocument::undo() {
    if (!can_undo()) return false;
    --position_;
    ++revision_;
    return true;
}

bool ExperimentDocument::redo() {
    if (!can_redo()) return false;
    ++position_;
    ++revision_;
    return true;
}

void ExperimentDocument::reset(const evo::Experiment& experiment, const std::string& path) {
    history_.assign(1, Entry{experiment, "open"});
    position_ = saved_position_ = 0;
    path_ = path;
    ++revision_;
    // Unique within the process, so two documents (New twice) never share an identity.
    static std::atomic<std::uint64_t> next_identity{1};
    identity_ = next_identity.fetch_add(1);
}

void ExperimentDocument::mark_saved(const std::string& path) {
    path_ = path;
    saved_position_ = position_;
}

std::string document_label(const ExperimentDocument& document) {
    return document.path().empty() ? std::string("untitled") : document.path();
}

}  // namespace bhm::app::gui
