#pragma once
// Reading what 'bhm evolve' leaves in a run directory, for export and the studio.
#include <string>

#include "evo/experiment/experiment.hpp"

namespace bhm::app {

struct RunChampion {
    evo::Experiment experiment;
    evo::Body body;  //!< framed, workspace-sized phenotype
    double fitness = 0.0;
    int generation = 0;
};

//! Reads RUN_DIR/run.json (the experiment) and RUN_DIR/champion.json. Throws std::runtime_error
//! naming the file and field when either is missing or malformed.
RunChampion load_run_champion(const std::string& run_dir);

}  // namespace bhm::app
