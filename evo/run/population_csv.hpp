#pragma once
// population.csv: the population after the last completed generation, one row per member in
// selection order, rewritten atomically with fitness.csv (run_output.hpp). It is what a plot of
// the population needs from outside the run: each member's fitness, age and volume (filled voxel
// count) and its Pareto layer, so the studio's Pareto plot (volume against fitness) can be drawn
// from a run directory during and after a run (app/gui/session/run_directory_watch.hpp). Nothing
// in it depends on wall time, so a resumed run writes the same file as its uninterrupted twin.
#include <string>

#include "evo/run/run_state.hpp"

namespace bhm::evo {

inline constexpr const char* kPopulationCsvFile = "population.csv";
inline constexpr const char* kPopulationCsvHeader =
    "generation,id,parent_id,fitness,age,voxels,active_voxels,pareto_rank,valid,diverged,"
    "exploits_checked,escaped,unanchored_fraction,detached_motion,base_motion_ratio,tentacle,"
    "thin_share";

//! The file's text for the state's population (state.generation, state.pareto_rank): numbers in
//! the C locale, fitness and measures in their shortest exact form, flags as 1 or 0 (the exploit
//! flags and their measures: evo/evaluate/exploit_flags.hpp; exploits_checked 0 for a result
//! from before exploit detection).
std::string population_csv(const RunState& state);

}  // namespace bhm::evo
