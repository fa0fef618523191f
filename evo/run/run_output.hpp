#pragma once
// The files of an evolution run directory (docs/evolution.md):
//   run.json              experiment as started, seed, version, rule changes
//   fitness.csv           one row per generation (HistoryRow), rewritten atomically each time
//   population.csv        the population after the last generation (population_csv.hpp)
//   champion.json         the current champion: genome, phenotype layers, fitness, generation found
//   champions/gen-NNNNN.json  each new champion, by the generation that found it
//   champion.vxa          the champion for VoxCAD (VXA 1.0)
//   checkpoint.json (+ checkpoint.prev.json)  see checkpoint.hpp
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/run/run_state.hpp"

namespace bhm::evo {

inline constexpr const char* kFitnessCsvHeader =
    "generation,evaluations,simulations,best_fitness,median_fitness,best_age,best_id,diverged,wall_"
    "s,best_escaped,best_detached_motion,best_tentacle,flagged_members,ended_early,mean_simulated_"
    "s,best_simulated_s,best_periodic_residual";

//! fitness.csv text: the header then one row per generation. Numbers in the C locale; fitness with
//! the shortest exact form, wall_s with millisecond resolution. NEAT runs (rows with species > 0)
//! add a last column, species.
std::string fitness_csv(const std::vector<HistoryRow>& history);

nlohmann::json champion_to_json(const Experiment& experiment, const ChampionRecord& champion);

//! run.json contents.
nlohmann::json run_info_json(const Experiment& original, const RunState& state);

class RunOutput {
  public:
    //! Creates the directory and its champions/ folder. Throws std::runtime_error naming the path.
    explicit RunOutput(std::string dir);
    const std::string& dir() const { return dir_; }
    std::string path(const std::string& name) const;

    void write_run_info(const Experiment& original, const RunState& state) const;
    void write_fitness_csv(const std::vector<HistoryRow>& history) const;
    //! population.csv (population_csv.hpp) for the state's population.
    void write_population_csv(const RunState& state) const;
    //! champion.json, champion.vxa and champions/gen-NNNNN.json.
    void write_champion(const Experiment& experiment, const ChampionRecord& champion) const;
    //! save_checkpoint (checkpoint.hpp), `current_is_damaged` included.
    void write_checkpoint(const RunState& state, bool current_is_damaged = false) const;

  private:
    std::string dir_;
};

}  // namespace bhm::evo
