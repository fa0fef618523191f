#include "app/gui/welcome/example_body.hpp"

#include <algorithm>
#include <exception>

#include "evo/evaluate/constraints.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/genome/rng.hpp"

namespace bhm::app::gui {

std::optional<evo::Body> example_body(const evo::Experiment& e, int draws) {
    try {
        const evo::Developer developer(e);
        const int enough = std::max(1, developer.space().cell_count() / 10);
        evo::Rng rng(e.evolution.seed);
        std::optional<evo::Phenotype> best;
        for (int k = 0; k < draws; ++k) {
            const evo::Genome genome =
                evo::random_genome(e.evolution.cppn, rng, developer.cppn_output_count());
            evo::Phenotype phenotype = developer.develop(genome);
            if (!evo::constraint_violation(e.fitness.constraints, e.boundary, developer.space(),
                                           phenotype)
                     .empty())
                continue;
            if (phenotype.designed_voxels >= enough) return std::move(phenotype.body);
            if (!best || phenotype.designed_voxels > best->designed_voxels)
                best = std::move(phenotype);
        }
        if (best) return std::move(best->body);
    } catch (const std::exception&) {
        // Not developable (a material missing, no design space): the thumbnail shows the
        // workspace alone.
    }
    return std::nullopt;
}

}  // namespace bhm::app::gui
