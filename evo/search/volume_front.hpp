#pragma once
// The Pareto front of volume against fitness (issue 44): of a set of bodies, those that no other
// body beats on both, i.e. none is at least as fit with no more voxels (minimised volume; no
// fewer when the volume is maximised) and strictly better in one. What the studio's Pareto plot
// highlights; it is the two-objective front, so it ignores age (AFPO's selection ranks on age as
// well: evo/search/afpo.hpp). Bodies of equal fitness and volume are on it together or not at
// all.
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct VolumePoint {
    double fitness = 0.0;  //!< maximised
    int voxels = 0;        //!< the body's volume: filled cells
};

//! on_front[i] for each point. `direction` says which way the volume counts: Minimize or
//! Maximize; Off counts as Minimize (the trade-off the plot shows by default: a smaller body that
//! moves as far is better).
std::vector<bool> volume_front(const std::vector<VolumePoint>& points, VolumeObjective direction);

}  // namespace bhm::evo
