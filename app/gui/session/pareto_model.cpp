#include "app/gui/session/pareto_model.hpp"

#include "evo/search/volume_front.hpp"

namespace bhm::app::gui {

std::vector<ParetoEntry> pareto_entries(const EvolutionSnapshot& run, ParetoAxis axis) {
    const bool active = axis == ParetoAxis::ActiveVoxels;
    std::vector<ParetoEntry> entries;
    std::vector<evo::VolumePoint> points;
    for (const auto& m : run.population) {
        if (!m.valid || m.diverged || m.fitness < 0.0) continue;  // no fitness to place
        const int x = active ? m.active_voxels : m.voxels;
        entries.push_back({m.id, m.fitness, x, false, run.has_champion && m.id == run.champion.id,
                           m.body != nullptr});
        points.push_back({m.fitness, x});
    }
    // Active voxels are only ever minimised (fitness.minimize_active_voxels).
    const auto front = evo::volume_front(
        points, active ? evo::VolumeObjective::Minimize : run.experiment.fitness.volume_objective);
    for (std::size_t k = 0; k < entries.size(); ++k)
        entries[k].on_front = front[k];
    return entries;
}

}  // namespace bhm::app::gui
