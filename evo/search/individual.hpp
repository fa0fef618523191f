#pragma once
// One member of the AFPO population: its genome, the phenotype it develops into and its result.
#include <cstdint>

#include "evo/evaluate/fitness.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/phenotype.hpp"

namespace bhm::evo {

struct Individual {
    std::int64_t id = 0;          //!< unique within a run, in creation order
    std::int64_t parent_id = -1;  //!< -1 for a random newcomer
    int age = 0;                  //!< AFPO age: generations since its lineage was a random newcomer
    int born_generation = 0;
    Genome genome;  //!< the body's CPPN; with evolution.controller fixed_body, the controller's
    //! evolution.controller coevolve only: the controller's CPPN (evo/genome/controller.hpp);
    //! empty (no outputs) otherwise
    Genome controller;
    Phenotype phenotype;   //!< developer.develop(genome); not stored in checkpoints
    FitnessReport report;  //!< report.fitness follows the current rules
    bool evaluated = false;
    bool valid = true;  //!< false only after a rule change made it break a constraint
};

}  // namespace bhm::evo
