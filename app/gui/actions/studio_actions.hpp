#pragma once
// Everything the user can do, as functions over the Studio: panels, the key-binding table and
// scripts call these, so a keyboard shortcut, a button and a script step run the same code.
// Failures never throw out of here: they become the status line (one line naming the file/field).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/studio.hpp"
#include "app/gui/view/viewport.hpp"

namespace bhm::app::gui {

//! Sets the status line (and the error flag) shown at the bottom of the window.
void set_status(Studio& studio, const std::string& message, bool is_error = false);

//! One status line naming every problem ("field: message; field: message"), prefixed by
//! `prefix`; the status bar's tooltip lists them one per line (studio.ui.edit_problems).
std::string describe_problems(const std::string& prefix, const std::vector<evo::Problem>& problems);

// --- Document ------------------------------------------------------------------------------
//! Validates and applies an edited experiment; on refusal the status names every problem
//! (studio.ui.edit_problems holds them). Returns true when applied (or unchanged).
bool apply_edit(Studio& studio, const evo::Experiment& next, const std::string& label);
void new_experiment(Studio& studio);
bool open_experiment(Studio& studio, const std::string& path);
//! The first start (welcome/welcome.hpp): what a newcomer starts with: the quick demo in the editor
//! (not "untitled" with the paper's 2000 generations and 48 h) behind the welcome, which holds
//! Start until it is closed. The demo opened on the user's behalf is not a recent file. False (the
//! status says why) when the quick demo is missing; the welcome opens anyway.
bool open_welcome(Studio& studio);
bool save_experiment_as(Studio& studio, const std::string& path);
bool save_experiment(Studio& studio);  //!< to the current path (Save As when untitled)
bool undo(Studio& studio);
//! The material library, read from studio.library.materials_dir on first use; nullptr (and
//! studio.library.materials_error) when it does not load.
const evo::MaterialLibrary* studio_material_library(Studio& studio);
//! "material library: FILE:(file): skipped: ... (and N more)", or "" when every entry read.
std::string material_library_warning(const evo::MaterialLibrary& library);
//! Fills material slot (0-based) from library material `id` (evo::apply_library_material, at the
//! experiment's temperature amplitude) as one undoable edit; values the library has no source for
//! keep the slot's. False when the id is unknown or the edit is refused.
bool choose_library_material(Studio& studio, std::size_t slot, const std::string& id);
bool redo(Studio& studio);

// --- Painter -------------------------------------------------------------------------------
bool cycle_face(Studio& studio, evo::Face face);
bool set_enclosure_thickness(Studio& studio, evo::Face face, int voxels);
bool paint_cell(Studio& studio, const std::array<int, 3>& cell);  //!< with the current brush

// --- Evolution -----------------------------------------------------------------------------
//! Starts a run of the document's experiment into studio.run.dir_field (a fresh folder under
//! default_runs_root() when empty), the same files and checkpoints as `bhm evolve`.
bool start_run(Studio& studio);
bool pause_run(Studio& studio);
bool resume_run(Studio& studio);
bool stop_run(Studio& studio);
bool resume_run_directory(Studio& studio, const std::string& run_dir);
//! The folder of the live session's run when it was stopped after at least one generation (its
//! checkpoint can be resumed); empty otherwise.
std::string stopped_run_folder(const Studio& studio);
//! Resume after Stop: the stopped run goes on from its last checkpoint, as Resume run on its
//! folder would. False when there is no such run (stopped_run_folder).
bool resume_stopped_run(Studio& studio);
//! The fallback when a resume failed (no usable checkpoint): the experiment the run was started
//! with (its run.json) becomes the editor's document and starts from generation 0 in a new
//! folder, as the CLI's message proposes. Refused while the editor holds unsaved edits.
bool restart_from_run_info(Studio& studio);
//! Sends the document's fitness rules (measure, constraints, objectives) and continuum-check
//! settings (evolution.verify) to the paused or running session, where they differ from the
//! run's; the population is re-scored before the next generation and the change is marked. A
//! refused check setting (CalculiX missing, out of range) sends nothing: false, and the status
//! says why.
bool apply_rules_to_run(Studio& studio);
//! The editor shows the live run's own document (the one it was started from, or the resumed
//! run's experiment): only then can its rule edits be sent to the run.
bool editing_run_document(const Studio& studio);
//! The live run's fitness rules as they will be for its next generation: the last ones sent to
//! it (Apply, Resume), else those in force; none while no run is loaded.
//! What a live run can take between generations is its fitness rules (measure, constraints,
//! objectives); boundary changes alter the bodies themselves and need a new run.
std::optional<evo::Fitness> run_fitness_rules(const Studio& studio);
//! The live run's continuum-check settings as they will be for its next generation: the last
//! ones sent to it, else those in force; none while no run is loaded.
std::optional<evo::LoopVerifySettings> run_verify_settings(const Studio& studio);
//! The run's document is in the editor and its evolution.verify differs from the live run's.
bool verify_differs_from_run(const Studio& studio);
//! The run's document is in the editor and its fitness rules or continuum-check settings differ
//! from the live run's (those already sent to it count: the message of edits to apply goes as
//! soon as they are sent).
bool rules_differ_from_run(const Studio& studio);
//! What Apply would send: "min fill 0.05; CalculiX checks every 2 generations, ..." ("" when
//! nothing differs).
std::string describe_rules_to_send(const Studio& studio);
//! The document's boundary (faces, frame, overrides) differs from the live run's: it applies to
//! the next run only.
bool boundary_differs_from_run(const Studio& studio);

//! Another run is about to be shown: the bodies of the one shown so far (and their simulations
//! in flight) go, so its champion never plays under the new run's name.
void forget_shown_bodies(Studio& studio);

// --- Run directory -------------------------------------------------------------------------
bool open_run_directory(Studio& studio, const std::string& run_dir);
void close_run_directory(Studio& studio);

// --- Bodies and replay ---------------------------------------------------------------------
//! Simulates population member `id` of the shown run for the 3D view (follow_champion off).
bool select_individual(Studio& studio, std::int64_t id);
//! The request that simulates a run's champion under the run's experiment and the champion's
//! measure (replay and Verify in FEM); throws when its body file cannot be read.
SimulationRequest champion_request(const Studio& studio, const ChampionEntry& entry);
//! Replays a champion of the run's history (champions/gen-N.json) in the 3D view, or beside the
//! body shown (compare). The run's rules with the measure the champion was found under.
bool replay_champion(Studio& studio, const ChampionEntry& entry, bool beside);
void clear_compared_body(Studio& studio);
//! Overlays another run directory's fitness history on the plots (thin); false when unreadable.
bool add_compared_run(Studio& studio, const std::string& run_dir);
void remove_compared_run(Studio& studio, std::size_t index);
//! The exploit flags of the body shown (its population member, the champion or a champion file
//! of the history with that id); null when unknown.
const evo::ExploitReport* shown_exploits(const Studio& studio);
//! Back to following the champion: its simulation is shown as soon as it is ready.
void follow_champion(Studio& studio);
void set_view_mode(Studio& studio, ViewMode mode);
void toggle_playback(Studio& studio);
void step_replay(Studio& studio, int frames);

// --- Verify in FEM (docs/verify.md) ------------------------------------------------------
//! Checks the body shown against CalculiX on the verifier's worker; the report goes to the shown
//! run's directory (verify/individual-<id>/). False (the status says why) without a body, a run
//! directory, or while a verification is running.
bool verify_shown_body(Studio& studio);
//! Replays a champion of the run's history and verifies it.
bool verify_champion(Studio& studio, const ChampionEntry& entry);
//! Shows a member of the current population (select_individual) and verifies it.
bool verify_individual(Studio& studio, std::int64_t id);
//! Shows the body of a report kept in the run directory (Analysis > FEM > Kept FEM reports)
//! with that report and its ghost, without solving: a member of the run's snapshot, a
//! champion of its history, or else a member of its checkpoint's population (a reopened run
//! directory lists only its champions). False (the status says why) when none holds the id.
bool show_kept_verification(Studio& studio, std::int64_t id);
//! Kills the solver of the verification in progress; nothing is written.
void cancel_verification(Studio& studio);
//! fem_overlay (what of it the 3D view draws) is view/viewport.hpp's.
//! The verdict as the studio shows it: with the tolerance it was judged by when the body was
//! compared ("agrees within 3.1 % (tolerance 10 %)"), so a reader never has to hover for it.
std::string fem_verdict_line(const FemVerification& verification);
//! Per frame (update_studio): takes the verifier's newest state, and looks up the report kept in
//! the run directory for a body newly shown.
void update_verification(Studio& studio);

// --- Camera --------------------------------------------------------------------------------
void set_named_view(Studio& studio, render::NamedView view);

// --- Export --------------------------------------------------------------------------------
// These need the GL context and the renderer; the implementations live in studio_app.cpp.

//! Per-frame housekeeping before the panels: takes new snapshots, starts champion simulations,
//! advances the replay clock.
void update_studio(Studio& studio);

}  // namespace bhm::app::gui
