#pragma once
// One member of a population as everything after the run loop sees it: the generation report
// (GenerationReport::population), the run directory's champion files (ChampionFile,
// run_directory.hpp) and the studio's tables (PopulationMember, app/gui/session/, which adds only
// the body it shares between frames). One shape, so a field added here reaches all three.
#include <cstdint>

#include <optional>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/run/loop_check.hpp"
#include "evo/search/individual.hpp"

namespace bhm::evo {

struct MemberSummary {
    std::int64_t id = 0;
    double fitness = 0.0;
    int age = 0;
    int voxels = 0;
    int active_voxels = 0;
    int pareto_rank = 0;  //!< 0 = on the Pareto front of (fitness up, age down[, active down])
    int species = 0;      //!< NEAT: its species id (0 for other algorithms)
    bool valid = true;    //!< false: breaks the current constraints
    bool diverged = false;
    //! Novelty search: its novelty in the last selection (behaviour distance, voxel lengths);
    //! negative when unknown (other algorithms, or a resumed run before its next generation).
    double novelty = -1.0;
    ExploitReport exploits;  //!< escaped / detached_motion / tentacle and their measures
    //! Its body's continuum check in the loop (evolution.verify), where one was made: the
    //! outcome and the deciding difference (the studio's badge). Only in generation reports.
    std::optional<LoopCheckOutcome> check;
    double check_worst = 0.0;
    double active_fraction() const {
        return voxels > 0 ? static_cast<double>(active_voxels) / voxels : 0.0;
    }
};

//! What an individual says of itself; the rank, species and novelty come from the selection.
MemberSummary summary_of(const Individual& individual);

}  // namespace bhm::evo
