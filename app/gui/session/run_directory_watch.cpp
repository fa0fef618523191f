#include "app/gui/session/run_directory_watch.hpp"

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
    fitness_mtime_ = champion_mtime_ = experiment_mtime_ = {};
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
    if (snapshot_ && run_t == experiment_mtime_ && fitness_t == fitness_mtime_ &&
        champion_t == champion_mtime_)
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
                     change.physics
                         ? describe_rule_change(info.started, info.started.fitness,
                                                info.rule_changes, i)
                         : std::string("fitness rules changed (") +
                               evo::kFitnessNames[static_cast<std::size_t>(change.fitness.measure)] +
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
            snap->population = {
                m};  // the files hold the champion; the population is in the checkpoint
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
    snapshot_ = std::move(snap);
    ++reloads_;
    return true;
}

}  // namespace bhm::app::gui
