#pragma once
// The Calibrate tab's actions (docs/studio.md, docs/calibration.md): show a body file, load a
// measured track onto the body shown, run the calibration on its own thread
// (session/calibration_session.hpp), cancel it, and apply the fitted values to the document as
// one recorded, undoable edit. Panels, scripts and tests call these; failures become the status
// line (one line naming the file or field), never exceptions.
#include <array>
#include <optional>
#include <string>

#include "app/gui/studio.hpp"
#include "app/gui/view/track_points.hpp"

namespace bhm::app::gui {

//! Simulates BODY.json (docs/experiment-format.md's body file) under the document's experiment
//! and shows it, as `bhm calibrate --body` would simulate it.
bool show_body_file(Studio& studio, const std::string& path);
//! Reads a track (docs/track-format.md) onto the body shown now and simulates that body at the
//! track's times (the preview drawn over the replay).
bool load_track(Studio& studio, const std::string& path);
//! Fits the ticked parameters (studio.calibration.fit_on) on the worker thread.
bool start_calibration(Studio& studio);
bool cancel_calibration(Studio& studio);
//! Writes the fitted values into the document (evo::copy_fitted_values) as one undoable edit
//! labelled with the values and the track; false when there is no finished calibration or the
//! edit is refused.
bool apply_calibration(Studio& studio);
//! After Apply: the track's body, when it is the one shown, is simulated again under the
//! calibrated experiment (labelled so) and nothing stays beside it in the split view.
void show_calibrated_body(Studio& studio);
//! Sends the fitted values to the live run as a rule change with physics
//! (EvolutionSession::change_physics): the run's physics with the fitted values in place, so
//! from the next generation every member is simulated again under them, the change is in
//! run.json, the checkpoint and the Fitness plot, and the status line says what changed. When
//! the editor shows the run's own document, the values also go into it as one undoable edit (so
//! the editor and the run agree). False (status line) without a finished calibration or a live
//! run, or when the run refuses the physics.
bool apply_calibration_to_run(Studio& studio);
//! The fit list the ticked boxes make ("E,amplitude").
std::string ticked_fit_list(const CalibrationState& calibration);
//! Whether --fit `name` applies to the experiment: the sine model's cte, amplitude, frequency
//! and phase_lag to a sine experiment, a muscle's rise_s, decay_s and contraction_strain to a
//! muscle one (evo::parse_fit_list's own rule), the rest to any.
bool fit_name_applies(const std::string& name, const evo::Experiment& experiment);

//! Per frame (update_studio): takes the newest snapshot and puts the end of a job on the status
//! line.
void update_calibration(Studio& studio);
//! The calibration is running (its clock, for the redraw gate).
bool calibration_running(const Studio& studio);

}  // namespace bhm::app::gui
