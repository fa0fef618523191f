#pragma once
// The one rule for how long a single body may be simulated, shared by `bhm simulate` and the
// Python module's simulate() so that neither can start a simulation that never ends
// (issue 26 N2: seconds=inf, 1e300 or 1e6 ran forever from Python).
#include <string>

#include "engine/model.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::app {

//! Empty when total_s can be simulated for this model under this experiment; otherwise one line
//! saying why: not a positive finite number, out of engine::limits' step budget, or shorter than
//! one sampling period of record_fps.
std::string simulation_seconds_problem(const engine::Model& model,
                                       const evo::Experiment& experiment, double total_s);

}  // namespace bhm::app
