#include "evo/run/run_output.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>

#include "bhm_version.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/formats/vxa.hpp"
#include "evo/genome/controller.hpp"
#include "evo/run/checkpoint.hpp"
#include "evo/run/population_csv.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/run/run_file_schema.hpp"

namespace bhm::evo {

namespace fs = std::filesystem;
using nlohmann::json;

std::string fitness_csv(const std::vector<HistoryRow>& history) {
    // NEAT runs add a species column; the others keep the header they always had.
    const bool species = std::any_of(history.begin(), history.end(),
                                     [](const HistoryRow& h) { return h.species > 0; });
    // Novelty search runs add their novelty and archive figures (docs/evolution.md).
    const bool novelty = std::any_of(history.begin(), history.end(),
                                     [](const HistoryRow& h) { return h.novelty.has_value(); });
    // Runs with continuum checks in the loop add theirs (docs/verify.md).
    const bool verify = std::any_of(history.begin(), history.end(),
                                    [](const HistoryRow& h) { return h.verify.has_value(); });
    std::string out = std::string(kFitnessCsvHeader) + (species ? ",species" : "") +
                      (novelty ? ",best_novelty,median_novelty,archive_size,archive_added,"
                                 "archive_threshold,champion_fitness"
                               : "") +
                      (verify ? ",verified,champion_agrees,worst_difference" : "") + "\n";
    for (const auto& h : history) {
        // Integers and the to_chars-based numbers never depend on the locale.
        const long long wall_ms = static_cast<long long>(h.wall_s * 1000.0 + 0.5);
        char wall[32];
        std::snprintf(wall, sizeof wall, "%lld.%03lld", wall_ms / 1000, wall_ms % 1000);
        out += std::to_string(h.generation) + "," + std::to_string(h.evaluations) + "," +
               std::to_string(h.simulations) + "," + engine::format_number(h.best_fitness) + "," +
               engine::format_number(h.median_fitness) + "," + std::to_string(h.best_age) + "," +
               std::to_string(h.best_id) + "," + std::to_string(h.diverged) + "," + wall + "," +
               (h.best_exploits.escaped ? "1," : "0,") +
               (h.best_exploits.detached_motion ? "1," : "0,") +
               (h.best_exploits.tentacle ? "1," : "0,") + std::to_string(h.flagged_members) + "," +
               std::to_string(h.ended_early) + "," + engine::format_number(h.mean_simulated_s) +
               "," + engine::format_number(h.best_simulated_s) + "," +
               engine::format_number(h.best_periodic_residual) +
               (species ? "," + std::to_string(h.species) : std::string());
        if (novelty) {
            const NoveltyRow n = h.novelty.value_or(NoveltyRow{});
            out += "," + engine::format_number(n.best_novelty) + "," +
                   engine::format_number(n.median_novelty) + "," + std::to_string(n.archive_size) +
                   "," + std::to_string(n.archive_added) + "," +
                   engine::format_number(n.archive_threshold) + "," +
                   engine::format_number(n.champion_fitness);
        }
        if (verify) {
            // Empty where nothing was checked: "no answer" is not "disagrees".
            const LoopCheckRow v = h.verify.value_or(LoopCheckRow{});
            out += "," + std::to_string(v.verified) + "," +
                   (v.champion_agrees ? (*v.champion_agrees ? "1" : "0") : "") + "," +
                   (v.worst_difference ? engine::format_number(*v.worst_difference) : "");
        }
        out += "\n";
    }
    return out;
}

json champion_to_json(const Experiment& experiment, const ChampionRecord& c) {
    return write_fields(champion_file_fields(), c, RunFileContext{"", &experiment, ""});
}

json run_info_json(const Experiment& original, const RunState& state) {
    RunInfo info;
    info.bhm_version = BHM_VERSION_STRING;
    info.seed = state.seed;
    info.started = original;
    info.rule_changes = state.rule_changes;
    return write_fields(run_info_fields(), info, RunFileContext{});
}

RunOutput::RunOutput(std::string dir) : dir_(std::move(dir)) {
    std::error_code ec;
    fs::create_directories(fs::path(dir_) / "champions", ec);
    if (ec)
        throw std::runtime_error(dir_ + ": cannot create the run directory (" + ec.message() + ")");
    // Refused now rather than after a generation of simulations.
    if (::access(dir_.c_str(), W_OK | X_OK) != 0) {
        const int error = errno;
        throw std::runtime_error(dir_ + ": the run directory is not writable (" +
                                 engine::error_text(error) + ")");
    }
}

std::string RunOutput::path(const std::string& name) const {
    return (fs::path(dir_) / name).string();
}

void RunOutput::write_run_info(const Experiment& original, const RunState& state) const {
    write_file_atomically(path(kRunInfoFile), run_info_json(original, state).dump(2) + "\n");
}

void RunOutput::write_fitness_csv(const std::vector<HistoryRow>& history) const {
    write_file_atomically(path(kFitnessCsvFile), fitness_csv(history));
}

void RunOutput::write_population_csv(const RunState& state) const {
    write_file_atomically(path(kPopulationCsvFile), population_csv(state));
}

void RunOutput::write_champion(const Experiment& experiment, const ChampionRecord& champion) const {
    const json record = champion_to_json(experiment, champion);
    const std::string text = record.dump(2) + "\n";
    char name[48];
    std::snprintf(name, sizeof name, "champions/gen-%05d.json", champion.generation_found);
    write_file_atomically(path(name), text);
    write_file_atomically(path(kChampionFile), text);
    save_vxa(path("champion.vxa"), experiment, champion.individual.phenotype.body);
    // The champion's controller on its own, reusable on another body (issue 44).
    if (record.contains("controller"))
        write_file_atomically(path(kControllerFile), record["controller"].dump(2) + "\n");
}

void RunOutput::write_checkpoint(const RunState& state, bool current_is_damaged) const {
    save_checkpoint(dir_, state, current_is_damaged);
}

}  // namespace bhm::evo
