#include "app/gui/session/run_directory_watch.hpp"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"

namespace bhm::app::gui {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::file_time_type mtime_or_zero(const fs::path& path) {
    std::error_code ec;
    const auto t = fs::last_write_time(path, ec);
    return ec ? fs::file_time_type{} : t;
}

// fitness.csv (evo/run/run_output.hpp): columns found by name, so added columns do not break us.
std::vector<GenerationRecord> read_fitness_csv(const fs::path& path) {
    std::istringstream in(engine::read_text(path.string(), engine::kLargeFileCap));
    std::string line;
    if (!std::getline(in, line)) return {};
    std::vector<std::string> header;
    {
        std::istringstream h(line);
        std::string cell;
        while (std::getline(h, cell, ','))
            header.push_back(cell);
    }
    auto column = [&](const char* name) {
        for (std::size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return static_cast<int>(i);
        throw std::runtime_error(path.string() + ": no '" + name + "' column");
    };
    const int c_gen = column("generation"), c_best = column("best_fitness"),
              c_median = column("median_fitness"), c_sims = column("simulations"),
              c_wall = column("wall_s");
    std::vector<GenerationRecord> records;
    std::int64_t simulations = 0;
    int row = 1;
    while (std::getline(in, line)) {
        ++row;
        if (line.empty()) continue;
        std::vector<std::string> cells;
        std::istringstream r(line);
        std::string cell;
        while (std::getline(r, cell, ','))
            cells.push_back(cell);
        if (cells.size() < header.size())
            throw std::runtime_error(path.string() + ": row " + std::to_string(row) + " has " +
                                     std::to_string(cells.size()) + " cells, expected " +
                                     std::to_string(header.size()));
        try {
            GenerationRecord g;
            g.generation = std::stoi(cells[static_cast<std::size_t>(c_gen)]);
            g.best_fitness = std::stod(cells[static_cast<std::size_t>(c_best)]);
            g.median_fitness = std::stod(cells[static_cast<std::size_t>(c_median)]);
            g.elapsed_s = std::stod(cells[static_cast<std::size_t>(c_wall)]);
            simulations += std::stoll(cells[static_cast<std::size_t>(c_sims)]);
            g.evaluations = simulations;
            records.push_back(g);
        } catch (const std::logic_error&) {
            throw std::runtime_error(path.string() + ": row " + std::to_string(row) +
                                     " is not numeric");
        }
    }
    return records;
}

json parse_json_file(const fs::path& path) {
    try {
        return json::parse(engine::read_text(path.string(), engine::kLargeFileCap));
    } catch (const json::exception& e) {
        throw std::runtime_error(path.string() + ": damaged, not valid JSON (" +
                                 evo::without_json_tags(e.what()) + ")");
    }
}

}  // namespace

void RunDirectoryWatch::open(const std::string& run_dir) {
    std::error_code ec;
    if (!fs::is_directory(run_dir, ec))
        throw std::runtime_error(run_dir + ": no such run directory");
    if (!fs::exists(fs::path(run_dir) / "run.json", ec) &&
        !fs::exists(fs::path(run_dir) / "fitness.csv", ec))
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
    const auto run_t = mtime_or_zero(dir / "run.json");
    const auto fitness_t = mtime_or_zero(dir / "fitness.csv");
    const auto champion_t = mtime_or_zero(dir / "champion.json");
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
            const json info = parse_json_file(dir / "run.json");
            json experiment = info.at("experiment");
            const std::string label = (dir / "run.json").string();
            snap->initial_measure = evo::parse_experiment(experiment, label).fitness.measure;
            snap->rule_changes.clear();
            for (const auto& change : info.value("rule_changes", json::array())) {
                experiment["fitness"] = change.at("fitness");
                snap->rule_changes.push_back(
                    {change.at("generation").get<int>(),
                     std::string("fitness rules changed (") +
                         change.at("fitness").value("measure", "?") + ")",
                     evo::parse_experiment(experiment, label).fitness.measure});
            }
            snap->experiment = evo::parse_experiment(experiment, label);
            snap->generation_budget = snap->experiment.evolution.generations;
        }
        if (fitness_t != fitness_mtime_ && fitness_t != fs::file_time_type{}) {
            snap->history = read_fitness_csv(dir / "fitness.csv");
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
            const json c = parse_json_file(dir / "champion.json");
            const std::string label = (dir / "champion.json").string();
            PopulationMember& m = snap->champion;
            m.id = c.at("id").get<std::int64_t>();
            m.fitness = c.at("fitness").get<double>();
            m.age = c.value("age", 0);
            m.voxels = c.value("voxels", 0);
            m.active_voxels = c.value("active_voxels", 0);
            m.body = std::make_shared<const evo::Body>(evo::parse_body(c.at("phenotype"), label));
            if (c.contains("report") && c.at("report").contains("exploits"))
                m.exploits = evo::exploits_from_json(c.at("report").at("exploits"));
            snap->has_champion = true;
            snap->champion_generation = c.value("generation_found", 0);
            snap->best_fitness = m.fitness;
            snap->population = {
                m};  // the files hold the champion; the population is in the checkpoint
        }
        snap->message = "run directory " + dir_ + " (read-only view, refreshed as it grows)";
        error_.clear();
    } catch (const json::exception& e) {
        // A field missing or of the wrong type (nlohmann's messages name no file).
        error_ = dir_ + ": run.json or champion.json is damaged (" +
                 evo::without_json_tags(e.what()) + ")";
        return false;
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
