#include "app/gui/session/run_directory_watch.hpp"

#include <algorithm>

#include "evo/run/checkpoint.hpp"
#include "evo/run/population_csv.hpp"
#include "evo/run/run_directory.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;

namespace {

fs::file_time_type mtime_or_zero(const fs::path& path) {
    std::error_code ec;
    const auto t = fs::last_write_time(path, ec);
    return ec ? fs::file_time_type{} : t;
}

//! The Run panel's history from fitness.csv (evo/run/run_directory.hpp): the rows that could be
//! read; a bad row is named in `problem` and ends the table.
std::vector<GenerationRecord> history_of(const evo::FitnessTable& table) {
    const std::size_t c_gen = table.column("generation"), c_best = table.column("best_fitness"),
                      c_median = table.column("median_fitness"),
                      c_sims = table.column("simulations"), c_wall = table.column("wall_s");
    std::vector<GenerationRecord> records;
    std::int64_t simulations = 0;
    for (const auto& row : table.rows) {
        GenerationRecord g;
        g.generation = static_cast<int>(row[c_gen]);
        g.best_fitness = row[c_best];
        g.median_fitness = row[c_median];
        g.elapsed_s = row[c_wall];
        simulations += static_cast<std::int64_t>(row[c_sims]);
        g.evaluations = simulations;
        records.push_back(g);
    }
    return records;
}

//! The population from population.csv (evo/run/population_csv.hpp), best fitness first as the
//! live session sorts it; no bodies (the champion's is added by the caller). A bad row ends the
//! table, as in fitness.csv.
std::vector<PopulationMember> population_of(const evo::FitnessTable& table) {
    const std::size_t c_id = table.column("id"), c_fitness = table.column("fitness"),
                      c_age = table.column("age"), c_voxels = table.column("voxels"),
                      c_active = table.column("active_voxels"),
                      c_rank = table.column("pareto_rank"), c_valid = table.column("valid"),
                      c_diverged = table.column("diverged"),
                      c_checked = table.column("exploits_checked"),
                      c_escaped = table.column("escaped"),
                      c_unanchored = table.column("unanchored_fraction"),
                      c_detached = table.column("detached_motion"),
                      c_base = table.column("base_motion_ratio"),
                      c_tentacle = table.column("tentacle"), c_thin = table.column("thin_share");
    std::vector<PopulationMember> members;
    for (const auto& row : table.rows) {
        PopulationMember m;
        m.id = static_cast<std::int64_t>(row[c_id]);
        m.fitness = row[c_fitness];
        m.age = static_cast<int>(row[c_age]);
        m.voxels = static_cast<int>(row[c_voxels]);
        m.active_voxels = static_cast<int>(row[c_active]);
        m.pareto_rank = static_cast<int>(row[c_rank]);
        m.valid = row[c_valid] != 0.0;
        m.diverged = row[c_diverged] != 0.0;
        m.exploits.checked = row[c_checked] != 0.0;
        m.exploits.escaped = row[c_escaped] != 0.0;
        m.exploits.unanchored_fraction = row[c_unanchored];
        m.exploits.detached_motion = row[c_detached] != 0.0;
        m.exploits.base_motion_ratio = row[c_base];
        m.exploits.tentacle = row[c_tentacle] != 0.0;
        m.exploits.thin_share = row[c_thin];
        members.push_back(std::move(m));
    }
    std::stable_sort(
        members.begin(), members.end(),
        [](const PopulationMember& a, const PopulationMember& b) { return a.fitness > b.fitness; });
    return members;
}

//! The champion's body and exploit report on its row of the population (the row keeps its own
//! fitness: champion.json has the one under the rules in force when it was found).
void attach_champion(EvolutionSnapshot& snap) {
    if (!snap.has_champion) return;
    for (auto& m : snap.population)
        if (m.id == snap.champion.id) {
            if (!m.body) m.body = snap.champion.body;
            m.exploits = snap.champion.exploits;
        }
}

}  // namespace

void RunDirectoryWatch::open(const std::string& run_dir) {
    std::error_code ec;
    if (!fs::is_directory(run_dir, ec))
        throw std::runtime_error(run_dir + ": no such run directory");
    if (!fs::exists(fs::path(run_dir) / evo::kRunInfoFile, ec) &&
        !fs::exists(fs::path(run_dir) / evo::kFitnessCsvFile, ec))
        throw std::runtime_error(run_dir +
                                 ": not a run directory (no run.json or fitness.csv; "
                                 "it is what `bhm evolve --out DIR` writes)");
    dir_ = run_dir;
    fitness_mtime_ = champion_mtime_ = experiment_mtime_ = population_mtime_ = {};
    snapshot_.reset();
    error_.clear();
}

void RunDirectoryWatch::close() {
    dir_.clear();
    snapshot_.reset();
    error_.clear();
}

bool RunDirectoryWatch::refresh() {
    if (dir_.empty()) return false;
    const fs::path dir(dir_);
    const auto run_t = mtime_or_zero(dir / evo::kRunInfoFile);
    const auto fitness_t = mtime_or_zero(dir / evo::kFitnessCsvFile);
    const auto champion_t = mtime_or_zero(dir / evo::kChampionFile);
    const auto population_t = mtime_or_zero(dir / evo::kPopulationCsvFile);
    if (snapshot_ && run_t == experiment_mtime_ && fitness_t == fitness_mtime_ &&
        champion_t == champion_mtime_ && population_t == population_mtime_)
        return false;
    auto snap = std::make_shared<EvolutionSnapshot>(snapshot_ ? *snapshot_ : EvolutionSnapshot{});
    snap->phase = RunPhase::Idle;
    snap->run_dir = dir_;
    snap->loaded = true;
    try {
        if (run_t != experiment_mtime_ || !snapshot_) {
            // run.json: the experiment as started plus every change of fitness rules.
            const evo::RunInfo info = evo::read_run_info(dir_);
            snap->initial_measure = info.started.fitness.measure;
            snap->rule_changes.clear();
            for (std::size_t i = 0; i < info.rule_changes.size(); ++i) {
                const auto& change = info.rule_changes[i];
                snap->rule_changes.push_back(
                    {change.generation,
                     change.physics ? describe_rule_change(info.started, info.started.fitness,
                                                           info.rule_changes, i)
                                    : std::string("fitness rules changed (") +
                                          evo::kFitnessNames[static_cast<std::size_t>(
                                              change.fitness.measure)] +
                                          ")",
                     change.fitness.measure});
            }
            snap->experiment = info.current();
            snap->generation_budget = snap->experiment.evolution.generations;
        }
        if (fitness_t != fitness_mtime_ && fitness_t != fs::file_time_type{}) {
            const evo::FitnessTable table = evo::read_fitness_table(dir_);
            snap->history = history_of(table);
            fitness_problem_ = table.problem;
            if (!snap->history.empty()) {
                const auto& last = snap->history.back();
                snap->generation = last.generation + 1;
                snap->elapsed_s = last.elapsed_s;
                snap->evaluations = last.evaluations;
                snap->simulations_per_s =
                    last.elapsed_s > 0.0 ? last.evaluations / last.elapsed_s : 0.0;
            }
        }
        if (champion_t != champion_mtime_ && champion_t != fs::file_time_type{}) {
            const evo::ChampionFile c = evo::read_champion_file(dir_, snap->experiment);
            PopulationMember& m = snap->champion;
            static_cast<evo::MemberSummary&>(m) = c;  // the summary part of the file
            m.body = std::make_shared<const evo::Body>(c.body);
            snap->has_champion = true;
            snap->champion_generation = c.generation_found;
            snap->best_fitness = m.fitness;
        }
        // population.csv where the run wrote one (runs before it: the champion alone).
        if (population_t != fs::file_time_type{}) {
            if (population_t != population_mtime_ || champion_t != champion_mtime_) {
                snap->population = population_of(evo::read_population_table(dir_));
                // Bodies developed earlier (load_bodies) for members still there; the rest go.
                std::map<std::int64_t, std::shared_ptr<const evo::Body>> kept;
                for (auto& m : snap->population)
                    if (const auto it = bodies_.find(m.id); it != bodies_.end()) {
                        m.body = it->second;
                        m.hash = hashes_[m.id];
                        kept.insert(*it);
                    }
                bodies_ = std::move(kept);
                attach_champion(*snap);
            }
        } else if (snap->has_champion) {
            snap->population = {snap->champion};
        }
        snap->message = fitness_problem_.empty()
                            ? "run directory " + dir_ + " (read-only view, refreshed as it grows)"
                            : fitness_problem_;
        error_.clear();
    } catch (const std::exception& e) {
        error_ = e.what();  // e.g. a file replaced mid-read: keep the last good view
        return false;
    }
    experiment_mtime_ = run_t;
    fitness_mtime_ = fitness_t;
    champion_mtime_ = champion_t;
    population_mtime_ = population_t;
    snapshot_ = std::move(snap);
    ++reloads_;
    return true;
}

bool RunDirectoryWatch::load_bodies() {
    if (dir_.empty() || !snapshot_) return false;
    try {
        const evo::LoadedCheckpoint loaded = evo::load_checkpoint(dir_);
        auto snap = std::make_shared<EvolutionSnapshot>(*snapshot_);
        bool changed = false;
        for (const auto& individual : loaded.state.population)
            for (auto& m : snap->population)
                if (m.id == individual.id && !m.body) {
                    m.body = std::make_shared<const evo::Body>(individual.phenotype.body);
                    m.hash = individual.phenotype.hash;
                    bodies_[m.id] = m.body;
                    hashes_[m.id] = m.hash;
                    changed = true;
                }
        if (changed) snapshot_ = std::move(snap);
        return changed;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

}  // namespace bhm::app::gui
