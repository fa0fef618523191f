#pragma once
// The experiment being edited in the studio: its file path, a dirty flag and an undo history.
// Every edit (a field of the Experiment panel, a face click, a painted voxel) goes through edit(),
// which validates the whole experiment first (evo::validate_experiment) and refuses an invalid
// one, so the document is always a valid experiment and undo/redo only ever restore valid ones.
// Experiments are small (a few kB), so the history keeps whole copies: simple and exact.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::app::gui {

class ExperimentDocument {
  public:
    ExperimentDocument();  //!< the default experiment (studio_defaults.hpp), untitled

    const evo::Experiment& experiment() const { return history_[position_].experiment; }
    const std::string& path() const { return path_; }  //!< empty while untitled
    bool dirty() const { return position_ != saved_position_; }
    //! Increases on every change, undo and redo included: caches keyed on it know when to rebuild.
    std::size_t revision() const { return revision_; }
    //! Changes only when a new or another file's experiment replaces this one (reset): a live run
    //! remembers the identity of the document it was started from, so edits to another document
    //! never reach it.
    std::uint64_t identity() const { return identity_; }

    //! Replaces the experiment with `next` when it is valid and records `label` for undo. Returns
    //! the validator's problems (nothing changes then); an unchanged experiment records nothing.
    std::vector<evo::Problem> edit(const evo::Experiment& next, const std::string& label);

    bool can_undo() const { return position_ > 0; }
    bool can_redo() const { return position_ + 1 < history_.size(); }
    //! Label of the edit that undo / redo would revert / reapply ("" when none).
    std::string undo_label() const;
    std::string redo_label() const;
    bool undo();
    bool redo();

    //! New or opened document: the history restarts from `experiment`, which counts as saved.
    void reset(const evo::Experiment& experiment, const std::string& path);
    //! After a successful save to `path`.
    void mark_saved(const std::string& path);

    //! Oldest entries are dropped beyond this many edits.
    static constexpr std::size_t kMaxHistory = 500;

  private:
    struct Entry {
        evo::Experiment experiment;
        std::string label;  //!< the edit that produced this entry
    };
    std::vector<Entry> history_;
    std::size_t position_ = 0;
    std::size_t saved_position_ = 0;
    std::size_t revision_ = 0;
    std::uint64_t identity_ = 0;
    std::string path_;
};

//! Label used in messages for the document's file ("untitled" when it has none).
std::string document_label(const ExperimentDocument& document);

}  // namespace bhm::app::gui
