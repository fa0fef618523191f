#pragma once
// evolution.controller = "coevolve" (issue 44): each individual carries a body CPPN (genome) and
// a controller CPPN (controller, evo/genome/controller.hpp). The wrapped algorithm breeds bodies
// as it always does (mutation, crossover, NEAT's species); then every new individual gets a
// controller: a newcomer (no parent in the last population) a random one, a child its parent's
// (the first parent's after a crossover) mutated by one of the six operators, and its phenotype
// is developed again with it. A child that cloned its parent's body is therefore new all the
// same and is evaluated. Carried members keep theirs. Selection is the wrapped algorithm's.
#include <memory>
#include <unordered_map>

#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {

//! The controller step above on a brood (controller_of: the last population's, by id).
void give_controllers(const GenerationContext& context,
                      const std::unordered_map<std::int64_t, Genome>& controller_of, Brood& brood,
                      Rng& rng);

std::unique_ptr<SearchAlgorithm> make_coevolve_search(std::unique_ptr<SearchAlgorithm> inner);

}  // namespace bhm::evo
