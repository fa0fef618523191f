#pragma once
// An example body for a preset's welcome thumbnail: what the preset evolves, rather than its empty
// workspace. A body of generation 0, drawn as evolution draws it (random CPPN genome with the
// experiment's CPPN settings and seed, developed, kept when it passes the experiment's
// constraints), so it needs no run and no file beyond the preset, and is the same at every start.
#include <optional>

#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

//! The first of the experiment's random generation-0 bodies (Rng(evolution.seed)) that passes its
//! constraints and fills at least a tenth of the design space (a one-voxel body shows nothing),
//! else the largest that passes; nullopt when none of `draws` passes or the experiment cannot be
//! developed (no passive or active material, empty design space). Workspace-sized, framed.
std::optional<evo::Body> example_body(const evo::Experiment& experiment, int draws = 50);

}  // namespace bhm::app::gui
