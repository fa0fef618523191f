// HyperNEAT (evolution.algorithm = "hyperneat"; Stanley, D'Ambrosio & Gauci 2009) as a
// SearchAlgorithm. The search is NEAT's own (speciation, mutation, crossover, innovation history:
// neat_search.cpp); what differs is the genome's meaning, which the Developer holds: an
// eight-input CPPN painting the connection weights of a substrate over the voxel lattice
// (evo/genome/hyperneat_substrate.hpp), whose outputs paint the body or the controller. So the
// algorithm is NEAT's object, and the checkpoint keeps NEAT's state for it (uses_neat).
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {

std::unique_ptr<SearchAlgorithm> make_hyperneat_search() {
    return make_neat_search();
}

}  // namespace bhm::evo
