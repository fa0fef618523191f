#include "evo/run/population_csv.hpp"

#include "engine/io/text_file.hpp"

namespace bhm::evo {

std::string population_csv(const RunState& state) {
    std::string out = std::string(kPopulationCsvHeader) + "\n";
    for (std::size_t k = 0; k < state.population.size(); ++k) {
        const Individual& m = state.population[k];
        const int rank = k < state.pareto_rank.size() ? state.pareto_rank[k] : 0;
        out += std::to_string(state.generation) + "," + std::to_string(m.id) + "," +
               std::to_string(m.parent_id) + "," + engine::format_number(m.report.fitness) + "," +
               std::to_string(m.age) + "," + std::to_string(m.phenotype.voxels) + "," +
               std::to_string(m.phenotype.active_voxels) + "," + std::to_string(rank) + "," +
               (m.valid ? "1," : "0,") + (m.report.diverged ? "1," : "0,");
        const ExploitReport& x = m.report.exploits;
        out += std::string(x.checked ? "1," : "0,") + (x.escaped ? "1," : "0,") +
               engine::format_number(x.unanchored_fraction) + "," +
               (x.detached_motion ? "1," : "0,") + engine::format_number(x.base_motion_ratio) +
               "," + (x.tentacle ? "1," : "0,") + engine::format_number(x.thin_share) + "\n";
    }
    return out;
}

}  // namespace bhm::evo
