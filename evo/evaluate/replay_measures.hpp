#pragma once
// The fitness measures of evo/evaluate/fitness.hpp recomputed from a replay, frame by frame ("so far"
// values: what evaluate_body would report had the run ended at that frame), for captions and
// analysis of recorded runs. Same definitions as MeasureTracker: reference at the first frame at
// or after settle_s, mass-weighted centre of mass, bend line from the base layer (first fixed
// face, x- if none) to the farthest filled layer. Replays store float positions, so values agree
// with a live evaluation to float precision.
#include <array>
#include <vector>

#include "engine/replay.hpp"
#include "evo/evaluate/fitness.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! One entry per replay frame, indexed like FitnessReport::measures. Throws std::invalid_argument
//! when a voxel's material is not in the experiment's palette.
std::vector<std::array<double, kMeasureCount>> replay_measures(const Experiment& experiment,
                                                               const engine::Replay& replay);

}  // namespace bhm::evo
