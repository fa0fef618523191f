#pragma once
// What File > New starts from: the paper's materials (Table 1) and timing, held at x-.
#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

//! Passive tissue and active muscle (E = 5 MPa, rho = 1000, nu = 0.35, CTE 0 / 0.01, friction
//! 1 / 0.5), 2 Hz actuation, 1 s settle + 10 s evaluation, the x- face fixed, an 8x8x7 workspace.
evo::Experiment default_experiment();

}  // namespace bhm::app::gui
