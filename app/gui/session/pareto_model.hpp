#pragma once
// What the studio's Pareto plot (Analysis > Volume vs fitness) shows of a run's population: each
// member with a fitness to place (valid, not diverged) as a point of volume (its filled voxel
// count) against fitness, marked where it is on the volume-vs-fitness front (evo/search/
// volume_front.hpp) in the direction of the run's fitness.volume_objective (minimised when off).
// The x axis may be the active voxels instead (the other size objective,
// fitness.minimize_active_voxels, always minimised). Built from the immutable snapshot on the UI
// thread; no ImGui here, so tests check it directly.
#include <cstdint>
#include <vector>

#include "app/gui/session/evolution_snapshot.hpp"

namespace bhm::app::gui {

//! What the plot's x axis counts.
enum class ParetoAxis { Volume, ActiveVoxels };

struct ParetoEntry {
    std::int64_t id = 0;
    double fitness = 0.0;
    int voxels = 0;  //!< the x axis: filled voxels, or active voxels (ParetoAxis::ActiveVoxels)
    bool on_front = false;
    bool champion = false;  //!< the run's champion (ringed)
    bool has_body = false;  //!< its body is at hand, so a click can show it
};

//! The snapshot's population members that have a fitness, in the population's order.
std::vector<ParetoEntry> pareto_entries(const EvolutionSnapshot& run,
                                        ParetoAxis axis = ParetoAxis::Volume);

}  // namespace bhm::app::gui
