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
//! table, as in fitness.csv. id, fitness and voxels are needed (a std::runtime_error names the
//! file and the column); the other columns take MemberSummary's defaults where a file lacks them.
std::vector<PopulationMember> population_of(const evo::FitnessTable& table) {
    const std::size_t c_id = table.column("id"), c_fitness = table.column("fitness"),
                      c_voxels = table.column("voxels");
    auto optional_column = [&](const char* name) {
        const auto it = std::find(table.header.begin(), table.header.end(), name);
        return static_cast<std::size_t>(it - table.header.begin());  // header.size(): absent
    };
    const std::size_t c_age = optional_column("age"), c_active = optional_column("active_voxels"),
                      c_rank = optional_column("pareto_rank"), c_valid = optional_column("valid"),
                      c_diverged = optional_column("diverged"),
                      c_checked = optional_column("exploits_checked"),
                      c_escaped = optional_column("escaped"),
                      c_unanchored = optional_column("unanchored_fraction"),
                      c_detached = optional_column("detached_motion"),
                      c_base = optional_column("base_motion_ratio"),
                      c_tentacle = optional_column("tentacle"),
                      c_thin = optional_column("thin_share");
    std::vector<PopulationMember> members;
    for (const auto& row : table.rows) {
        auto at = [&](std::size_t c, double fallback) {
            return c < row.size() ? row[c] : fallback;
        };
        PopulationMember m;
        m.id = static_cast<std::int64_t>(row[c_id]);
        m.fitness = row[c_fitness];
        m.voxels = static_cast<int>(row[c_voxels]);
        m.age = static_cast<int>(at(c_age, m.age));
        m.active_voxels = static_cast<int>(at(c_active, m.active_voxels));
        m.pareto_rank = static_cast<int>(at(c_rank, m.pareto_rank));
        m.valid = at(c_valid, 1.0) != 0.0;
        m.diverged = at(c_diverged, 0.0) != 0.0;
        m.exploits.checked = at(c_checked, 0.0) != 0.0;
        m.exploits.escaped = at(c_escaped, 0.0) != 0.0;
        m.exploits.unanchored_fraction = at(c_unanchored, 0.0);
        m.exploits.detached_motion = at(c_detached, 0.0) != 0.0;
        m.exploits.base_motion_ratio = at(c_base, 1.0);
        m.exploits.tentacle = at(c_tentacle, 0.0) != 0.0;
        m.exploits.thin_share = at(c_thin, 0.0);
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
    population_problem_.clear();
    bodies_.clear();  // another run's ids
    hashes_.clear();
}

void RunDirectoryWatch::close() {
    dir_.clear();
    snapshot_.reset();
    error_.clear();
    population_problem_.clear();
    bodies_.clear();
    hashes_.clear();
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
                // A population.csv that cannot be read is said, and the champion stands alone:
                // the rest of the run is still shown.
                population_problem_.clear();
                try {
                    const evo::FitnessTable table = evo::read_population_table(dir_);
                    snap->population = population_of(table);
                    population_problem_ = table.problem;
                } catch (const std::exception& e) {
                    population_problem_ = e.what();
                    snap->population.clear();
                    if (snap->has_champion) snap->population = {snap->champion};
                }
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
        snap->message = !fitness_problem_.empty()      ? fitness_problem_
                        : !population_problem_.empty() ? population_problem_
                                                       : "run directory " + dir_ +
                                                             " (read-only view, refreshed as it "
                                                             "grows)";
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
