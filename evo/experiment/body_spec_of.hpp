#pragma once
// From an experiment and a body to the engine's input: the one place that maps the experiment's
// boundary conditions, enclosure, overrides, materials, actuation and timing onto a BodySpec.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! Places the body at the origin of the workspace, adds the enclosure frame (passive material,
//! per-face thickness) and the voxel overrides (empty / material). The result has the workspace
//! size.
Body apply_frame_and_overrides(const Experiment& experiment, const Body& body);

//! The engine input for a body already framed (apply_frame_and_overrides): voxels in a face layer
//! marked fixed and voxels overridden as fixed are held; actuation starts at settle_s; per-voxel
//! phase is 0 (uniform) or drawn from phase_seed (random). Throws std::invalid_argument.
engine::BodySpec make_body_spec(const Experiment& experiment, const Body& framed_body,
                                std::uint64_t phase_seed = 0);

//! The engine settings of an experiment without a body (voxel size, damping, actuation with its
//! start at settle_s, environment, dt_fraction, rotary_inertia_scale): make_body_spec fills the
//! rest.
engine::BodySpec make_settings_spec(const Experiment& experiment);

//! The experiment file's field for a BodySpec field named by engine::limits ("dt_fraction" ->
//! "simulation.dt_fraction"); materials[k].x and unknown names are returned unchanged.
std::string experiment_field_of(const std::string& body_spec_field);

//! (cells of a workspace-sized lattice, x fastest) 1 where the engine holds the cell: the layer of
//! every face marked fixed and every voxel overridden as fixed; what make_body_spec uses.
std::vector<std::uint8_t> held_cells(const Boundary& boundary, std::array<int, 3> size);

//! Total simulated time of one evaluation: settle_s + evaluate_s.
inline double evaluation_seconds(const Experiment& e) {
    return e.simulation.settle_s + e.simulation.evaluate_s;
}

}  // namespace bhm::evo
