#pragma once
// The one rule for how long a single body may be simulated, shared by `bhm simulate`, the Python
// module's simulate() and `bhm calibrate` so that none can start a simulation that never ends
// (issue 26 N2: seconds=inf, 1e300 or 1e6 ran forever from Python; issue 41 R1: a track's
// time_offset_s of 1e6 did the same in bhm calibrate).
#include <string>

#include "engine/model.hpp"
#include "evo/calibrate/measured_track.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::app {

//! Empty when total_s is a positive finite number of seconds within engine::limits' step budget
//! for this model under this experiment; otherwise one line saying why, with the steps and hours
//! it would need. What every simulation obeys, whatever it records.
std::string simulation_budget_problem(const engine::Model& model,
                                      const evo::Experiment& experiment, double total_s);

//! simulation_budget_problem, and for a simulation recorded at record_fps (bhm simulate, the
//! Python module): a sampling period shorter than the whole simulation.
std::string simulation_seconds_problem(const engine::Model& model,
                                       const evo::Experiment& experiment, double total_s);

//! simulation_budget_problem for a simulation from 0 to the track's last time (what each of a
//! calibration's simulations runs), as "TRACK: FIELD: why" naming the field that set that time
//! (evo::track_end_field). The track's times are its samples, so record_fps does not enter.
std::string track_budget_problem(const engine::Model& model, const evo::Experiment& experiment,
                                 const evo::MeasuredTrack& track);

}  // namespace bhm::app
