#pragma once
// Aligning two NEAT genomes by innovation number (Stanley & Miikkulainen 2002, section 3.2, Fig. 4)
// and their compatibility distance (section 3.3, eq. 1):
//   delta = c1 E / N + c2 D / N + c3 W-bar
// E = excess genes (innovation beyond the other genome's largest), D = disjoint genes (the other
// unmatched ones), W-bar = mean |weight difference| of matching genes (0 when none match),
// N = 1, or with neat.normalize_by_size the paper's normalisation: connection genes of the larger
// genome, 1 when both have fewer than 20. Only connection genes count, as in the paper.
#include <cstddef>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/genome.hpp"

namespace bhm::evo {

struct GeneAlignment {
    //! Edge index pairs (in a, in b) with the same innovation number, in increasing innovation.
    std::vector<std::pair<std::size_t, std::size_t>> matching;
    std::vector<std::size_t> disjoint_a, disjoint_b;  //!< edge indices
    std::vector<std::size_t> excess_a, excess_b;
};

//! Both genomes must carry history (every edge an innovation number).
GeneAlignment align_genes(const Genome& a, const Genome& b);

//! The normaliser N above (kSmallGenomeGenes = 20).
inline constexpr std::size_t kSmallGenomeGenes = 20;
double compatibility_distance(const Genome& a, const Genome& b, const NeatSettings& settings);

}  // namespace bhm::evo
